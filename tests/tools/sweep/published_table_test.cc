// results/table1/README.md's Table I is the published report's: every row's runs, mean A with its interval,
// max A, crashes, the paper's crash count and the box share equal results/table1/report.md, and
// the verdict counts equal results/table1/findings.csv. Re-publishing Table I without updating
// the README (or the other way round) fails here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace msb {
namespace {

const std::string kSource = MSB_SOURCE_DIR;

std::vector<std::string> readLines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(' '), b = s.find_last_not_of(' ');
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

// A markdown table row's cells.
std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::stringstream ss(row.substr(1));
  for (std::string c; std::getline(ss, c, '|');) out.push_back(trim(c));
  return out;
}

// The rows of the table whose header starts with `header`, up to the first line that is not a row.
std::vector<std::vector<std::string>> tableAfter(const std::vector<std::string>& lines, const std::string& header) {
  std::vector<std::vector<std::string>> rows;
  auto it = std::find_if(lines.begin(), lines.end(), [&](const std::string& l) { return l.rfind(header, 0) == 0; });
  if (it == lines.end()) return rows;
  for (it += 2; it != lines.end() && !it->empty() && (*it)[0] == '|'; ++it) rows.push_back(cells(*it));
  return rows;
}

// "no OVDE" → "no_ovde", "MonoSpheres" → "monospheres".
std::string methodKey(std::string s) {
  for (char& c : s) c = c == ' ' ? '_' : char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string replaceAll(std::string s, const std::string& from, const std::string& to) {
  for (size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size())) s.replace(p, from.size(), to);
  return s;
}

TEST(PublishedTable, TheTablesReadmeIsTheReportsRowForRow) {
  const auto report = readLines(kSource + "/results/table1/report.md");
  const auto readme = readLines(kSource + "/results/table1/README.md");
  const auto layout = tableAfter(report, "| world | method | method type |");
  const auto beyond = tableAfter(report, "| world | method | box share |");
  const auto table = tableAfter(readme, "| world | method | runs | msbench mean A");
  ASSERT_FALSE(layout.empty());
  ASSERT_EQ(table.size(), layout.size()) << "README Table I and report.md list different rows";
  std::map<std::string, std::string> box_share;
  for (const auto& r : beyond) box_share[r[0] + "/" + r[1]] = r[2].substr(0, r[2].find(' '));
  for (size_t i = 0; i < table.size(); ++i) {
    const auto& md = table[i];
    const auto& rep = layout[i];
    const std::string row = md[0] + " " + md[1];
    EXPECT_EQ(md[0], rep[0]) << row;
    EXPECT_EQ(methodKey(md[1]), rep[1]) << row;
    EXPECT_EQ(md[2], rep[3]) << row << ": runs";
    EXPECT_EQ(md[3], rep[4] + " / " + rep[5]) << row << ": mean A [CI] / max";
    EXPECT_EQ(md[4], rep[6] + " / " + rep[7]) << row << ": the paper's mean / max";
    EXPECT_EQ(md[5], rep[8]) << row << ": crashes";
    EXPECT_EQ(md[6], replaceAll(rep[9], "p = ", "")) << row << ": the paper's crashes";
    EXPECT_EQ(md[7], box_share[rep[0] + "/" + rep[1]]) << row << ": box share";
  }
}

// The row of `rows` (a report's Table I layout) for `world` and `method`.
std::vector<std::vector<std::string>>::const_iterator rowOf(const std::vector<std::vector<std::string>>& rows,
                                                            const std::string& world, const std::string& method) {
  return std::find_if(rows.begin(), rows.end(), [&](const auto& r) { return r[0] == world && r[1] == method; });
}

// A cell's first word ("6953 [5778, 7788]" → "6953").
std::string firstWord(const std::string& c) { return c.substr(0, c.find(' ')); }

TEST(PublishedTable, TheReadmesShortTableIsTheReports) {
  // README: "| world | MonoSpheres (paper) | box share | published code | authors' worlds and
  // configuration | Grid (paper) | Grid, authors' |", the paper-bearing cells "mean (paper's
  // mean)"; results/table1's report gives MonoSpheres, the box share and the grid,
  // results/table1_published's the published code's MonoSpheres mean, results/table1_reference's
  // the two methods in the authors' worlds and configuration (the cave's grid is grid_fast).
  const auto report = readLines(kSource + "/results/table1/report.md");
  const auto layout = tableAfter(report, "| world | method | method type |");
  const auto beyond = tableAfter(report, "| world | method | box share |");
  const auto published =
      tableAfter(readLines(kSource + "/results/table1_published/report.md"), "| world | method | method type |");
  const auto reference =
      tableAfter(readLines(kSource + "/results/table1_reference/report.md"), "| world | method | method type |");
  const auto table = tableAfter(readLines(kSource + "/README.md"), "| world | MonoSpheres (paper) |");
  ASSERT_EQ(table.size(), 4u);
  for (const auto& md : table) {
    ASSERT_EQ(md.size(), 7u) << md[0];
    for (const auto& [col, method] : {std::pair<size_t, std::string>{1, "monospheres"}, {5, "grid"}}) {
      const auto rep = rowOf(layout, md[0], method);
      ASSERT_NE(rep, layout.end()) << md[0] << " " << method;
      EXPECT_EQ(md[col], firstWord((*rep)[4]) + " (" + (*rep)[6] + ")") << md[0] << " " << method;
    }
    const auto pub = rowOf(published, md[0], "monospheres");
    ASSERT_NE(pub, published.end()) << md[0];
    EXPECT_EQ(md[3], firstWord((*pub)[4])) << md[0];
    const auto b = rowOf(beyond, md[0], "monospheres");
    ASSERT_NE(b, beyond.end()) << md[0];
    EXPECT_EQ(md[2], firstWord((*b)[2])) << md[0];
    const auto ref = rowOf(reference, md[0], "monospheres");
    const auto ref_grid = rowOf(reference, md[0], md[0] == "cave" ? "grid_fast" : "grid");
    ASSERT_NE(ref, reference.end()) << md[0];
    ASSERT_NE(ref_grid, reference.end()) << md[0];
    EXPECT_EQ(md[4], firstWord((*ref)[4])) << md[0];
    EXPECT_EQ(md[6], firstWord((*ref_grid)[4])) << md[0];
  }
}

// results/table1_reference/README.md's table is its report's: each row's mean A with its
// interval, crashes and box share.
TEST(PublishedTable, TheReferenceTablesReadmeIsItsReportsRowForRow) {
  const std::string dir = kSource + "/results/table1_reference/";
  const auto report = readLines(dir + "report.md");
  const auto layout = tableAfter(report, "| world | method | method type |");
  const auto beyond = tableAfter(report, "| world | method | box share |");
  const auto table = tableAfter(readLines(dir + "README.md"), "| world | row | paper mean / max |");
  ASSERT_EQ(table.size(), layout.size()) << "the README's table and report.md list different rows";
  for (size_t i = 0; i < table.size(); ++i) {
    const auto& md = table[i];
    const auto& rep = layout[i];
    const std::string row = md[0] + " " + md[1];
    EXPECT_EQ(md[0], rep[0]) << row;
    EXPECT_EQ(md[2], rep[6] + " / " + rep[7]) << row << ": the paper's mean / max";
    EXPECT_EQ(replaceAll(md[5], "**", ""), rep[4]) << row << ": mean A [CI]";
    EXPECT_EQ(md[6].rfind(firstWord(rep[9]), 0), 0u) << row << ": crashes " << rep[9];  // after the earned column
    const auto b = rowOf(beyond, rep[0], rep[1]);
    ASSERT_NE(b, beyond.end()) << row;
    EXPECT_EQ(md[7], firstWord((*b)[2])) << row << ": box share";
  }
}

TEST(PublishedTable, TheReadmesVerdictCountsAreTheFindings) {
  std::map<std::string, int> verdicts;
  for (const auto& l : readLines(kSource + "/results/table1/findings.csv")) {
    for (const char* v : {",holds,", ",fails,", ",undecided,"})
      if (l.find(v) != std::string::npos) ++verdicts[v];
  }
  std::ostringstream want;
  want << "**" << verdicts[",holds,"] << " hold, " << verdicts[",fails,"] << " fail, " << verdicts[",undecided,"]
       << " undecided**";
  const auto readme = readLines(kSource + "/README.md");
  EXPECT_TRUE(std::any_of(readme.begin(), readme.end(),
                          [&](const std::string& l) { return l.find(want.str()) != std::string::npos; }))
      << "README does not say " << want.str();
  // And the reference table's counts, in README and its own README.
  std::map<std::string, int> reference;
  for (const auto& l : readLines(kSource + "/results/table1_reference/findings.csv"))
    for (const char* v : {",holds,", ",fails,", ",undecided,"})
      if (l.find(v) != std::string::npos) ++reference[v];
  std::ostringstream counts;
  counts << reference[",holds,"] << " hold, " << reference[",fails,"] << " fail, " << reference[",undecided,"]
         << " undecided";
  EXPECT_TRUE(
      std::any_of(readme.begin(), readme.end(),
                  [&](const std::string& l) { return l.find("**" + counts.str() + "**") != std::string::npos; }))
      << "README does not say " << counts.str();
  const auto reference_readme = readLines(kSource + "/results/table1_reference/README.md");
  EXPECT_TRUE(std::any_of(reference_readme.begin(), reference_readme.end(),
                          [&](const std::string& l) { return l.find(counts.str()) != std::string::npos; }))
      << "results/table1_reference/README.md does not say " << counts.str();
  const auto table_readme = readLines(kSource + "/results/table1/README.md");
  EXPECT_TRUE(std::any_of(table_readme.begin(), table_readme.end(),
                          [&](const std::string& l) { return l.find(want.str()) != std::string::npos; }))
      << "results/table1/README.md does not say " << want.str();
}

}  // namespace
}  // namespace msb
