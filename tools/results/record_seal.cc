#include "tools/results/record_seal.h"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <openssl/sha.h>

#include <cstdlib>

#include "core/common/input_file.h"

namespace msb {

namespace {

std::string hex(const unsigned char* bytes, size_t n) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (size_t i = 0; i < n; ++i) {
    out += digits[bytes[i] >> 4];
    out += digits[bytes[i] & 15];
  }
  return out;
}

// What the seal covers: the record without its seals, then coverage.csv.
std::string sealedContent(const nlohmann::json& metrics, const std::string& coverage_csv) {
  nlohmann::json content = metrics;
  content.erase("record_digest");
  content.erase("record_seal");
  return content.dump() + "\n" + coverage_csv;
}

}  // namespace

EvaluatorKey readEvaluatorKey(const std::filesystem::path& file) {
  EvaluatorKey key;
  key.file = file.string();
  try {
    key.secret = readInputFile(file, InputLimits{kMaxEvaluatorKeyBytes + 1});
  } catch (const InputFileError& e) {
    throw InputFileError(std::string("evaluator key: ") + e.what());
  }
  if (!key.secret.empty() && key.secret.back() == '\n') key.secret.pop_back();
  if (key.secret.size() < kMinEvaluatorKeyBytes || key.secret.size() > kMaxEvaluatorKeyBytes)
    throw InputFileError("evaluator key " + key.file + ": holds " + std::to_string(key.secret.size()) +
                         " bytes; a key has " + std::to_string(kMinEvaluatorKeyBytes) + " to " +
                         std::to_string(kMaxEvaluatorKeyBytes) + " (e.g. `head -c 32 /dev/urandom > FILE`)");
  // The id: SHA-256 of a domain label and the key, its first 8 bytes.
  const std::string labelled = std::string("msbench evaluator key id") + '\0' + key.secret;
  unsigned char digest[SHA256_DIGEST_LENGTH];
  SHA256(reinterpret_cast<const unsigned char*>(labelled.data()), labelled.size(), digest);
  key.id = hex(digest, 8);
  return key;
}

SealingKey sealingKeyFromEnvironment() {
  SealingKey out;
  const char* file = std::getenv(kEvaluatorKeyFileVariable);
  if (!file || !*file) return out;
  try {
    out.key = readEvaluatorKey(file);
  } catch (const InputFileError& e) {
    out.problem = std::string("$") + kEvaluatorKeyFileVariable + ": " + e.what();
  }
  return out;
}

const SealingKey& processSealingKey() {
  static const SealingKey key = sealingKeyFromEnvironment();
  return key;
}

std::string recordSeal(const EvaluatorKey& key, const nlohmann::json& metrics, const std::string& coverage_csv) {
  const std::string text = sealedContent(metrics, coverage_csv);
  unsigned char mac[EVP_MAX_MD_SIZE];
  unsigned int n = 0;
  HMAC(EVP_sha256(), key.secret.data(), int(key.secret.size()), reinterpret_cast<const unsigned char*>(text.data()),
       text.size(), mac, &n);
  return "hmac-sha256:" + key.id + ":" + hex(mac, n);
}

std::string sealKeyId(const nlohmann::json& metrics) {
  const auto it = metrics.find("record_seal");
  if (it == metrics.end() || !it->is_string()) return "";
  const std::string seal = it->get<std::string>();
  const std::string prefix = "hmac-sha256:";
  if (seal.rfind(prefix, 0) != 0 || seal.size() != prefix.size() + 16 + 1 + 64 || seal[prefix.size() + 16] != ':')
    return "";
  // Hex digits only: the id is shown in messages and reports, and the record is a stranger's file.
  const std::string id = seal.substr(prefix.size(), 16);
  return id.find_first_not_of("0123456789abcdef") == std::string::npos ? id : "";
}

bool writtenBeforeKeyedSeals(const nlohmann::json& metrics) {
  if (metrics.contains("record_format")) return false;
  // The build's version: 0.1.x wrote no record_format; a later one always does.
  const auto v = metrics.find("versions");
  if (v == metrics.end() || !v->is_object() || !v->contains("msbench") || !(*v)["msbench"].is_string()) return true;
  return (*v)["msbench"].get<std::string>().rfind("0.1.", 0) == 0;
}

SealCheck checkRecordSeal(const EvaluatorKey& key, const nlohmann::json& metrics, const std::string& coverage_csv) {
  if (writtenBeforeKeyedSeals(metrics)) return SealCheck::kPreSeal;
  const std::string id = sealKeyId(metrics);
  if (id.empty()) return SealCheck::kSelfSealed;
  if (id != key.id) return SealCheck::kOtherKey;
  // Compared in constant time: the MAC is the secret's witness.
  const std::string expected = recordSeal(key, metrics, coverage_csv);
  const std::string given = metrics["record_seal"].get<std::string>();
  return CRYPTO_memcmp(expected.data(), given.data(), expected.size()) == 0 ? SealCheck::kEvaluated
                                                                            : SealCheck::kTampered;
}

}  // namespace msb
