// Sets an environment variable for the scope and restores its previous value (or its absence)
// on exit. Used by tests that compare results for several FDR_THREADS values.
#pragma once
#include <cstdlib>
#include <string>

namespace fdr {

class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* v = std::getenv(name)) old_ = v, had_ = true;
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (had_) setenv(name_.c_str(), old_.c_str(), 1);
    else unsetenv(name_.c_str());
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  std::string name_, old_;
  bool had_ = false;
};

// FDR_THREADS=n for the scope.
class ThreadsEnv : public ScopedEnv {
 public:
  explicit ThreadsEnv(int n) : ScopedEnv("FDR_THREADS", std::to_string(n)) {}
};

}  // namespace fdr
