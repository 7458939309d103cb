// Errors with documented exit codes; every user-facing failure is an fdr::Error.
#pragma once
#include <stdexcept>
#include <string>

namespace fdr {

// Process exit codes: scripts depend on them, so never renumber.
enum class ExitCode : int {
  kOk = 0,
  kInternal = 1,         // a bug: an invariant failed inside fdrmesh
  kUsage = 2,            // bad command line (unknown option, missing value, bad number)
  kInputUnreadable = 3,  // missing file, unreadable file/layer, unknown format
  kInputMalformed = 4,   // file readable but its content cannot be parsed (line/field named)
  kInvalidGeometry = 5,  // PSLG/geometry invalid: crossing or zero-length segments, duplicates, no polygons
  kInvalidSpacing = 6,   // spacing f <= 0 or non-finite, raster not covering the domain, nodata everywhere
  kWorkLimit = 7,        // Steiner cap reached, or the estimated work is refused up front
  kOutputError = 8,      // output cannot be written
  kCrsError = 9,         // unknown or unusable CRS
  kCheckFailed = 10,     // --check found a violated mesh invariant
  kCancelled = 11,       // cancelled by the caller (progress callback returned false)
};

class Error : public std::runtime_error {
 public:
  Error(ExitCode code, const std::string& what) : std::runtime_error(what), code_(code) {}
  ExitCode code() const { return code_; }
  int exit_code() const { return static_cast<int>(code_); }

 private:
  ExitCode code_;
};

const char* exit_code_name(ExitCode c);

}  // namespace fdr
