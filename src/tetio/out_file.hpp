// All-or-nothing output for the 3D writers: each file is written under a unique temporary name in
// the target's folder and renamed onto the target only once complete, so a failed or interrupted
// run leaves no half-written mesh.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace fdr::tetio {

class OutFile {
 public:
  explicit OutFile(std::string target);  // creates "<target>.tmp-XXXXXX"; Error(kOutputError)
  ~OutFile();                            // removes the temporary file unless committed
  OutFile(const OutFile&) = delete;
  OutFile& operator=(const OutFile&) = delete;

  // Buffered writing; a failed write is Error(kOutputError) naming the target.
  void write(std::string_view bytes);
  void write_raw(const void* data, std::size_t n) { write(std::string_view(static_cast<const char*>(data), n)); }
  // Text with shortest round-trip numbers (reads back bit for bit).
  OutFile& str(std::string_view s) { write(s); return *this; }
  OutFile& num(double v);
  OutFile& num(std::int64_t v);
  OutFile& sp() { return str(" "); }
  OutFile& nl() { return str("\n"); }

  // Flushes, closes and renames onto the target.
  void commit();
  const std::string& target() const { return target_; }
  const std::string& temp_path() const { return temp_; }

 private:
  void flush();
  std::string target_, temp_;
  std::FILE* file_ = nullptr;
  std::string buf_;
  bool done_ = false;
};

// Commits several files as one: when a rename fails, the targets already renamed are removed so
// that no partial set (e.g. a .node without its .ele) remains.
void commit_all(const std::vector<OutFile*>& files);

}  // namespace fdr::tetio
