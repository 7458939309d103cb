// All-or-nothing output: temporary file next to the target, renamed when complete.
#include "tetio/out_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include "base/error.hpp"

namespace fdr::tetio {
namespace {

constexpr std::size_t kFlushBytes = 1 << 20;

[[noreturn]] void fail_output(const std::string& target, const std::string& why) {
  throw Error(ExitCode::kOutputError, target + ": " + why);
}

}  // namespace

OutFile::OutFile(std::string target) : target_(std::move(target)) {
  std::string name = target_ + ".tmp-XXXXXX";
  const int fd = ::mkstemp(name.data());
  if (fd < 0) {
    const int e = errno;
    fail_output(target_, std::string("cannot create a file in its folder: ") + std::strerror(e));
  }
  temp_ = name;
  // mkstemp gives 0600; the finished file gets what a plain create would (0666 less the umask).
  const mode_t mask = ::umask(022);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  file_ = ::fdopen(fd, "wb");
  if (!file_) {
    const int e = errno;
    ::close(fd);
    ::unlink(temp_.c_str());
    fail_output(target_, std::string("cannot open the temporary file: ") + std::strerror(e));
  }
  buf_.reserve(kFlushBytes + 4096);
}

OutFile::~OutFile() {
  if (done_) return;
  if (file_) std::fclose(file_);
  ::unlink(temp_.c_str());
}

void OutFile::write(std::string_view bytes) {
  if (bytes.size() >= kFlushBytes) {
    flush();
    if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) {
      const int e = errno;
      fail_output(target_, std::string("write failed: ") + std::strerror(e));
    }
    return;
  }
  buf_.append(bytes);
  if (buf_.size() >= kFlushBytes) flush();
}

OutFile& OutFile::num(double v) {
  char tmp[40];
  auto r = std::to_chars(tmp, tmp + sizeof tmp, v);
  buf_.append(tmp, r.ptr);
  return *this;
}

OutFile& OutFile::num(std::int64_t v) {
  char tmp[24];
  auto r = std::to_chars(tmp, tmp + sizeof tmp, v);
  buf_.append(tmp, r.ptr);
  return *this;
}

void OutFile::flush() {
  if (buf_.empty()) return;
  if (std::fwrite(buf_.data(), 1, buf_.size(), file_) != buf_.size()) {
    const int e = errno;
    fail_output(target_, std::string("write failed: ") + std::strerror(e));
  }
  buf_.clear();
}

void OutFile::commit() {
  flush();
  std::FILE* f = file_;
  file_ = nullptr;
  bool bad = std::fflush(f) != 0 || std::ferror(f) != 0;
  int e = errno;
  if (std::fclose(f) != 0 && !bad) {
    bad = true;
    e = errno;
  }
  if (bad) fail_output(target_, std::string("write failed: ") + std::strerror(e));
  if (std::rename(temp_.c_str(), target_.c_str()) != 0) {
    e = errno;
    fail_output(target_, std::string("cannot move the finished file into place: ") + std::strerror(e));
  }
  done_ = true;
}

void commit_all(const std::vector<OutFile*>& files) {
  for (std::size_t i = 0; i < files.size(); ++i) {
    try {
      files[i]->commit();
    } catch (...) {
      for (std::size_t j = 0; j < i; ++j) ::unlink(files[j]->target().c_str());
      throw;
    }
  }
}

}  // namespace fdr::tetio
