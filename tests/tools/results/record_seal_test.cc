// Evaluator-keyed seals (tools/results/record_seal.h, docs/integrity.md): a key file read with
// clear errors; a record sealed under the key verifies; an edit, a forger's re-seal (the FNV
// digest recomputed, as anyone can), another key, no key and a pre-seal build are each told apart.
#include "tools/results/record_seal.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/common/input_file.h"
#include "tools/results/run_record.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

fs::path keyFile(const std::string& name, const std::string& bytes) {
  const fs::path d = fs::path(::testing::TempDir()) / "msb_record_seal";
  fs::create_directories(d);
  std::ofstream(d / name, std::ios::binary) << bytes;
  return d / name;
}

// A FIFO where the key file should be: refused at once, never waited on.
fs::path fifo() {
  const fs::path p = fs::path(::testing::TempDir()) / "msb_record_seal" / "fifo";
  fs::create_directories(p.parent_path());
  fs::remove(p);
  EXPECT_EQ(mkfifo(p.c_str(), 0600), 0);
  return p;
}

nlohmann::json record() {
  return {{"status", "completed"},
          {"record_format", kRecordFormat},
          {"coverage", {{"area_m2", 3644.0}}},
          {"score", {{"earned", 13238.0}}},
          {"versions", {{"msbench", "0.2.0"}}}};
}

// What msbench writes: the keyed seal, then the digest over everything else.
nlohmann::json sealed(nlohmann::json m, const EvaluatorKey& key, const std::string& csv) {
  m["record_seal"] = recordSeal(key, m, csv);
  m["record_digest"] = recordDigest(m, csv);
  return m;
}

TEST(RecordSeal, AKeyFileIsReadWithItsIdAndBadOnesAreNamed) {
  const EvaluatorKey key = readEvaluatorKey(keyFile("k1", "0123456789abcdef0123456789abcdef\n"));
  EXPECT_EQ(key.secret, "0123456789abcdef0123456789abcdef");  // one trailing newline dropped
  EXPECT_EQ(key.id.size(), 16u);
  EXPECT_EQ(key.secret.find(key.id), std::string::npos);
  EXPECT_EQ(readEvaluatorKey(keyFile("k1b", "0123456789abcdef0123456789abcdef")).id, key.id);
  EXPECT_NE(readEvaluatorKey(keyFile("k2", "another key of 32 bytes, say....")).id, key.id);
  for (const auto& [file, why] : {std::pair<fs::path, std::string>{keyFile("short", "too short"), "holds 9 bytes"},
                                  {keyFile("long", std::string(5000, 'k')), "more than the limit"},
                                  {keyFile("empty", ""), "holds 0 bytes"},
                                  {fs::path(::testing::TempDir()) / "msb_record_seal", "a directory"},
                                  {fifo(), "a FIFO"},
                                  {fs::path(::testing::TempDir()) / "msb_record_seal/none", "file not found"}}) {
    try {
      readEvaluatorKey(file);
      ADD_FAILURE() << file << " was read as a key";
    } catch (const InputFileError& e) {
      EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  }
}

TEST(RecordSeal, OnlyTheEvaluatorsKeyVerifiesAndEveryOtherRecordIsToldApart) {
  const EvaluatorKey key = readEvaluatorKey(keyFile("ev", "the evaluator's own key, 32 bytes"));
  const EvaluatorKey other = readEvaluatorKey(keyFile("other", "a submitter's key of his own make"));
  const std::string csv = "t_s,area_m2\n0,0\n10,3644\n";
  const nlohmann::json m = sealed(record(), key, csv);
  EXPECT_EQ(m["record_seal"].get<std::string>().rfind("hmac-sha256:" + key.id + ":", 0), 0u) << m.dump();
  EXPECT_EQ(checkRecordSeal(key, m, csv), SealCheck::kEvaluated);
  EXPECT_EQ(sealKeyId(m), key.id);

  // A raised score, re-sealed as a forger can (the digest is public): the keyed seal fails.
  nlohmann::json forged = m;
  forged["score"]["earned"] = 28887.0;
  forged["record_digest"] = recordDigest(forged, csv);
  EXPECT_EQ(checkRecordSeal(key, forged, csv), SealCheck::kTampered);
  EXPECT_EQ(checkRecordSeal(key, m, csv + "20,9000\n"), SealCheck::kTampered);  // coverage.csv edited
  // Sealed with a key of his own: another key's record, never the evaluator's.
  EXPECT_EQ(checkRecordSeal(key, sealed(record(), other, csv), csv), SealCheck::kOtherKey);
  // Written without a key; or its seal removed; or a seal naming the key with a made-up MAC.
  nlohmann::json self = record();
  self["record_seal"] = kSelfSealedValue;
  EXPECT_EQ(checkRecordSeal(key, self, csv), SealCheck::kSelfSealed);
  self.erase("record_seal");
  EXPECT_EQ(checkRecordSeal(key, self, csv), SealCheck::kSelfSealed);
  nlohmann::json made_up = m;
  made_up["record_seal"] = "hmac-sha256:" + key.id + ":" + std::string(64, '0');
  EXPECT_EQ(checkRecordSeal(key, made_up, csv), SealCheck::kTampered);
  // A key id that is not hex (terminal escapes, markup) is no keyed seal.
  nlohmann::json hostile = m;
  hostile["record_seal"] = "hmac-sha256:\x1b[2J<b>x|y</b>!!" + std::string(1, ':') + std::string(64, '0');
  EXPECT_EQ(sealKeyId(hostile), "");
  EXPECT_EQ(checkRecordSeal(key, hostile, csv), SealCheck::kSelfSealed);
}

TEST(RecordSeal, PreSealIsDecidedByTheBuildThatWroteTheRecordNotByMissingKeys) {
  const EvaluatorKey key = readEvaluatorKey(keyFile("ev2", "the evaluator's own key, 32 bytes"));
  nlohmann::json old = {{"status", "completed"}, {"versions", {{"msbench", "0.1.0"}}}};
  EXPECT_TRUE(writtenBeforeKeyedSeals(old));
  EXPECT_EQ(checkRecordSeal(key, old, ""), SealCheck::kPreSeal);
  // A record of a keyed build with its record_format and seal deleted is not pre-seal.
  nlohmann::json stripped = record();
  stripped.erase("record_format");
  EXPECT_FALSE(writtenBeforeKeyedSeals(stripped));
  EXPECT_EQ(checkRecordSeal(key, stripped, ""), SealCheck::kSelfSealed);
}

}  // namespace
}  // namespace msb
