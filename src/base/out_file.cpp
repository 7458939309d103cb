// All-or-nothing file output: temporary file next to the target, renamed when complete.
#include "base/out_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include "base/error.hpp"

namespace fdr {

void fail_output(const std::string& path, const std::string& reason) {
  throw Error(ExitCode::kOutputError, path + ": " + reason);
}

TempFile::TempFile(const std::string& target) : target_(target) {
  std::string name = target + ".tmp-XXXXXX";
  fd_ = ::mkstemp(name.data());
  if (fd_ < 0) {
    const int e = errno;
    fail_output(target, std::string("cannot create a temporary file next to it: ") + std::strerror(e));
  }
  temp_ = name;
  // mkstemp makes the file 0600; give the final file the usual permissions (0666 minus umask).
  const mode_t mask = ::umask(022);
  ::umask(mask);
  ::fchmod(fd_, 0666 & ~mask);
}

TempFile::~TempFile() {
  if (!done_) discard();
}

void TempFile::release_for_library() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  ::unlink(temp_.c_str());
}

std::FILE* TempFile::stream() {
  if (!file_) {
    file_ = ::fdopen(fd_, "wb");
    if (!file_) {
      const int e = errno;
      fail_output(target_, std::string("cannot open temporary file: ") + std::strerror(e));
    }
    fd_ = -1;  // now owned by file_
  }
  return file_;
}

void TempFile::close_stream() {
  if (!file_) return;
  std::FILE* f = file_;
  file_ = nullptr;
  bool bad = std::fflush(f) != 0 || std::ferror(f) != 0;
  int e = errno;
  if (std::fclose(f) != 0 && !bad) {
    bad = true;
    e = errno;
  }
  if (bad) fail_output(target_, std::string("write failed: ") + std::strerror(e));
}

void TempFile::commit() {
  close_stream();
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
  if (std::rename(temp_.c_str(), target_.c_str()) != 0) {
    const int e = errno;
    fail_output(target_, std::string("cannot move the finished file into place: ") + std::strerror(e));
  }
  done_ = true;
}

void TempFile::discard() {
  if (file_) std::fclose(file_);
  file_ = nullptr;
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  ::unlink(temp_.c_str());
  // SQLite (GeoPackage) may leave journal files next to an aborted database.
  for (const char* s : {"-journal", "-wal", "-shm"}) ::unlink((temp_ + s).c_str());
  done_ = true;
}

void commit_all(const std::vector<TempFile*>& files) {
  for (std::size_t i = 0; i < files.size(); ++i) {
    try {
      files[i]->commit();
    } catch (...) {
      for (std::size_t j = 0; j < i; ++j) ::unlink(files[j]->target().c_str());
      throw;
    }
  }
}

void TextOut::write(std::string_view bytes) {
  if (bytes.size() < kFlush) {
    str(bytes);
    return;
  }
  flush();
  if (std::fwrite(bytes.data(), 1, bytes.size(), f_) != bytes.size()) {
    const int e = errno;
    fail_output(target_, std::string("write failed: ") + std::strerror(e));
  }
}

TextOut& TextOut::num(double v) {
  char tmp[64];
  auto r = std::to_chars(tmp, tmp + sizeof tmp, v);
  buf_.append(tmp, r.ptr);
  return *this;
}

TextOut& TextOut::num(std::int64_t v) {
  char tmp[32];
  auto r = std::to_chars(tmp, tmp + sizeof tmp, v);
  buf_.append(tmp, r.ptr);
  return *this;
}

TextOut& TextOut::num(std::uint64_t v) {
  char tmp[32];
  auto r = std::to_chars(tmp, tmp + sizeof tmp, v);
  buf_.append(tmp, r.ptr);
  return *this;
}

void TextOut::flush() {
  if (buf_.empty()) return;
  if (std::fwrite(buf_.data(), 1, buf_.size(), f_) != buf_.size()) {
    const int e = errno;
    fail_output(target_, std::string("write failed: ") + std::strerror(e));
  }
  buf_.clear();
}

void OutFile::commit() {
  flush();
  temp_->commit();
}

void commit_outputs(const std::vector<OutFile*>& files) {
  std::vector<TempFile*> temps;
  temps.reserve(files.size());
  for (OutFile* f : files) {
    f->flush();
    temps.push_back(&f->temp());
  }
  commit_all(temps);
}

}  // namespace fdr
