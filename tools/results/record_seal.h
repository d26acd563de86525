// Evaluator-keyed seals of run records (docs/integrity.md): an HMAC-SHA256 (OpenSSL) over a
// run's metrics.json and coverage.csv under a key only the evaluator holds, so that a record a
// submitter forged or re-sealed is told from one msbench wrote on the evaluator's machine.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace msb {

/// The environment variable naming the evaluator's key file (the key itself never sits in the
/// environment, which a process of the same user can read from /proc).
inline constexpr const char* kEvaluatorKeyFileVariable = "MSBENCH_EVALUATOR_KEY_FILE";

/// Fewest and most bytes of a key file (e.g. `head -c 32 /dev/urandom > key`).
inline constexpr size_t kMinEvaluatorKeyBytes = 16;
inline constexpr size_t kMaxEvaluatorKeyBytes = 4096;

/// The record format of this build (metrics.json `record_format`): 2 since records carry
/// `record_seal`. Records without it were written by builds before keyed seals (pre-seal).
inline constexpr int kRecordFormat = 2;

/// An evaluator's key: its bytes and a public identifier that names it without revealing it.
struct EvaluatorKey {
  std::string secret;  ///< the file's bytes, one trailing newline removed
  std::string id;      ///< 16 hex digits of SHA-256 over a domain label and the secret
  std::string file;    ///< where it was read from, for messages
};

/// Reads a key file: a regular file of kMinEvaluatorKeyBytes..kMaxEvaluatorKeyBytes. Throws
/// InputFileError naming the file and the reason (missing, unreadable, too short or too long).
EvaluatorKey readEvaluatorKey(const std::filesystem::path& file);

/// The key a run seals with: the file $MSBENCH_EVALUATOR_KEY_FILE names, or none.
struct SealingKey {
  std::optional<EvaluatorKey> key;
  std::string problem;  ///< why the variable is set but no key was read ("" otherwise)
};

/// Reads $MSBENCH_EVALUATOR_KEY_FILE now (unset or empty: no key, no problem).
SealingKey sealingKeyFromEnvironment();

/// sealingKeyFromEnvironment(), read once per process (every run of a sweep or a Python session
/// seals with the key the process started with).
const SealingKey& processSealingKey();

/// The seal of a record under `key`: "hmac-sha256:<key id>:<64 hex>" over metrics.json's content
/// without `record_digest` and `record_seal` (compact, sorted keys), a newline, and coverage.csv.
std::string recordSeal(const EvaluatorKey& key, const nlohmann::json& metrics, const std::string& coverage_csv);

/// The value of `record_seal` in a record written without an evaluator key.
inline constexpr const char* kSelfSealedValue = "self-sealed";

/// What a record's seal says under an evaluator's key.
enum class SealCheck {
  kEvaluated,   ///< sealed under this key, content unchanged
  kSelfSealed,  ///< written without an evaluator key (or its seal is not a keyed one)
  kPreSeal,     ///< written by a build before keyed seals (no `record_format`)
  kOtherKey,    ///< sealed under another evaluator's key
  kTampered,    ///< sealed under this key, but changed since (or re-sealed by a forger)
};

/// Whether a record was written by a build before keyed seals: it has no `record_format` and its
/// `versions.msbench` is 0.1.x (or absent, as in the oldest records). A record from a later build
/// without `record_format` is not pre-seal: its seal was removed.
bool writtenBeforeKeyedSeals(const nlohmann::json& metrics);

/// Checks `metrics` (with coverage.csv's bytes) against `key`.
SealCheck checkRecordSeal(const EvaluatorKey& key, const nlohmann::json& metrics, const std::string& coverage_csv);

/// The key id a record's keyed seal names ("" if it has none).
std::string sealKeyId(const nlohmann::json& metrics);

}  // namespace msb
