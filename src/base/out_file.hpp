// All-or-nothing file output shared by every writer: a file is written under a unique temporary
// name in the target's folder and renamed onto the target only once complete, so a failed or
// interrupted run leaves no half-written file.
#pragma once
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace fdr {

// Output error "<path>: <reason>" (ExitCode::kOutputError).
[[noreturn]] void fail_output(const std::string& path, const std::string& reason);

// A temp file "<target>.tmp-XXXXXX" next to `target`, reserved with mkstemp. commit() renames it
// onto the target; if never committed the destructor removes it (plus any SQLite sidecars).
class TempFile {
 public:
  explicit TempFile(const std::string& target);  // throws kOutputError (e.g. missing folder)
  ~TempFile();
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const std::string& path() const { return temp_; }
  const std::string& target() const { return target_; }
  // Closes the reserved descriptor and removes the empty file so a library (GDAL, netCDF) can
  // create it itself under the same unique name.
  void release_for_library();
  // Opens the reserved file for buffered writing (owned; closed by close_stream()).
  std::FILE* stream();
  // Flushes and closes the stream, throwing kOutputError on any write error (disk full ...).
  void close_stream();
  void commit();   // rename temp -> target; throws kOutputError
  void discard();  // remove the temp file now

 private:
  std::string target_, temp_;
  int fd_ = -1;
  std::FILE* file_ = nullptr;
  bool done_ = false;
};

// Commits several temp files together: if a later rename fails, the targets already renamed are
// removed again so no partial set of files (e.g. a .node without its .ele) remains.
void commit_all(const std::vector<TempFile*>& files);

// Buffered output with shortest round-trip number formatting (std::to_chars), so numbers read
// back bit for bit.
class TextOut {
 public:
  TextOut(std::FILE* f, std::string target) : f_(f), target_(std::move(target)) { buf_.reserve(kFlush + 256); }
  TextOut(const TextOut&) = delete;
  TextOut& operator=(const TextOut&) = delete;

  // Bytes as they are; a block larger than the buffer goes straight to the file.
  void write(std::string_view bytes);
  void write_raw(const void* data, std::size_t n) { write(std::string_view(static_cast<const char*>(data), n)); }
  TextOut& str(std::string_view s) { buf_.append(s); maybe_flush(); return *this; }
  TextOut& ch(char c) { buf_.push_back(c); return *this; }
  TextOut& num(double v);
  TextOut& num(std::int64_t v);
  TextOut& num(std::uint64_t v);
  TextOut& num(int v) { return num(static_cast<std::int64_t>(v)); }
  TextOut& num(unsigned v) { return num(static_cast<std::uint64_t>(v)); }
  TextOut& sp() { return ch(' '); }
  TextOut& nl() { buf_.push_back('\n'); maybe_flush(); return *this; }
  void flush();

 private:
  static constexpr std::size_t kFlush = 1 << 20;
  void maybe_flush() { if (buf_.size() >= kFlush) flush(); }
  std::FILE* f_;
  std::string target_;
  std::string buf_;
};

// A file written through TextOut into a TempFile: the writers' usual case.
class OutFile : public TextOut {
 public:
  explicit OutFile(const std::string& target) : OutFile(std::make_unique<TempFile>(target)) {}
  // Flushes, closes and renames onto the target.
  void commit();
  const std::string& target() const { return temp_->target(); }
  const std::string& temp_path() const { return temp_->path(); }
  TempFile& temp() { return *temp_; }

 private:
  explicit OutFile(std::unique_ptr<TempFile> t) : TextOut(t->stream(), t->target()), temp_(std::move(t)) {}
  std::unique_ptr<TempFile> temp_;
};

// commit_all for OutFiles: flushed first, then renamed as one set.
void commit_outputs(const std::vector<OutFile*>& files);

}  // namespace fdr
