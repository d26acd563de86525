// TUM files from trajectory.csv: 8 columns copied from the CSV, the estimate only when the file
// has the VIO's full orientation, and bad files refused naming the file and line.
#include "tools/results/trajectory_export.h"

#include <gtest/gtest.h>

#include "core/common/input_file.h"
#include "tools/results/flight_records.h"

namespace msb {
namespace {

// A row with every field set.
TrajectoryRow row() {
  return {0.1,          Vec3(1, 2, 3), Quat(0.5, 0.5, 0.5, 0.5), Vec3::Zero(), Vec3(1.5, 2, 3), 0.2,
          Vec3::Zero(), 0.0,           Quat(0.9, 0.1, 0.2, 0.3)};
}

TEST(TrajectoryExport, TumRowsCarryTheCsvsNumbersAndTheEstimatesFullOrientation) {
  const TrajectoryRow r = row();
  const TumTrajectories t = tumFromTrajectoryCsv(trajectoryCsv({r, r}), "trajectory.csv");
  EXPECT_EQ(t.rows, 2);
  EXPECT_NE(t.truth.find("\n0.100 1 2 3 0.5 0.5 0.5 0.5\n"), std::string::npos) << t.truth;
  EXPECT_NE(t.estimate.find("\n0.100 1.5 2 3 0.1 0.2 0.3 0.9\n"), std::string::npos) << t.estimate;
  // A file of before est_q*: the truth alone.
  const std::string old =
      "t,x,y,z,qw,qx,qy,qz,vx,vy,vz,est_x,est_y,est_z,est_yaw,ref_x,ref_y,ref_z,ref_yaw\n"
      "0.000,0,2,0,1,0,0,0,0,0,0,0,2,0,0,0,2,0,0\n";
  const TumTrajectories o = tumFromTrajectoryCsv(old, "old.csv");
  EXPECT_EQ(o.rows, 1);
  EXPECT_TRUE(o.estimate.empty());
}

TEST(TrajectoryExport, ABadFileIsRefusedNamingFileAndLine) {
  const std::string csv = trajectoryCsv({row()});
  const std::string header = csv.substr(0, csv.find('\n') + 1);
  auto refused = [](const std::string& text) -> std::string {
    try {
      tumFromTrajectoryCsv(text, "t.csv");
    } catch (const InputFileError& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_NE(refused("a,b\n1,2\n").find("t.csv: line 1"), std::string::npos);
  EXPECT_NE(refused(header).find("no rows"), std::string::npos);
  EXPECT_NE(refused(header + "1,2,3\n").find("t.csv: line 2: expected 23 cells, got 3"), std::string::npos);
  std::string row = csv.substr(header.size());
  row.replace(0, row.find(','), "nan");
  EXPECT_NE(refused(header + row).find("'nan' is not a finite number"), std::string::npos) << refused(header + row);
}

}  // namespace
}  // namespace msb
