// Rowid tables' B-trees written page by page into a closed SQLite file (see sqlite_bulk.hpp).
//
// What is written, from SQLite's file-format document:
// - A table-leaf page: header [0x0D, first freeblock (0), cell count, start of the cell content
//   area, fragmented bytes (0)], the cell pointers (2 bytes each, in key order), free space,
//   then the cells packed to the end of the usable area. A cell: varint payload size, varint
//   rowid, the record (no overflow: every record here fits in a page, which is checked).
// - A table-interior page: header [0x05, 0, cell count, content start, 0, right-most child], the
//   cell pointers, then the cells: 4-byte child page, varint key = the largest rowid of that
//   child's subtree; the right-most child holds the larger rowids.
// - The table's root page keeps its number (sqlite_master names it): the top node of the new
//   tree is written there, every other node to new pages appended to the file, never to the
//   lock-byte page (the page holding file offset `pending_byte`).
// - The header: database size in pages (offset 28), the file change counter (24) and the
//   version-valid-for number (92) bumped together, so SQLite trusts the size.
// All multi-byte integers are big-endian. Same rows, same pages whatever the thread count: the
// leaves are packed in chunks of rows fixed before any is packed (each starts a leaf).
#include "io/sqlite_bulk.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cerrno>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <mutex>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "io/detail.hpp"

namespace fdr::io::detail {

namespace {

constexpr std::size_t kChunkBytes = std::size_t{4} << 20;  // cells packed together (a chunk starts a leaf)

int varint_len(std::uint64_t v) {
  if (v <= 0x7F) return 1;
  if (v >> 56) return 9;
  int n = 1;
  while (v >>= 7) ++n;
  return n;
}

char* put_varint(char* p, std::uint64_t v) {
  if (v <= 0x7F) {
    *p = static_cast<char>(v);
    return p + 1;
  }
  if (v >> 56) {  // nine bytes: eight of seven bits, the last of eight
    p[8] = static_cast<char>(v & 0xFF);
    v >>= 8;
    for (int i = 7; i >= 0; --i) {
      p[i] = static_cast<char>((v & 0x7F) | 0x80);
      v >>= 7;
    }
    return p + 9;
  }
  const int n = varint_len(v);
  for (int i = n - 1; i >= 0; --i) {
    p[i] = static_cast<char>((v & 0x7F) | (i == n - 1 ? 0 : 0x80));
    v >>= 7;
  }
  return p + n;
}

void put_be(char* p, std::uint64_t v, int bytes) {
  for (int i = bytes - 1; i >= 0; --i) {
    p[i] = static_cast<char>(v & 0xFF);
    v >>= 8;
  }
}

std::uint64_t get_be(const unsigned char* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v = (v << 8) | p[i];
  return v;
}

}  // namespace

Record& Record::type(std::uint64_t t) {
  if (ntypes_ == kMaxColumns) throw Error(ExitCode::kInternal, "SQLite record with more than 32 columns");
  types_[ntypes_++] = t;
  type_bytes_ += static_cast<std::size_t>(varint_len(t));
  return *this;
}

// The record header's size: the serial types' varints and its own size's varint.
std::size_t Record::header_size() const {
  std::size_t k = 1;
  while (static_cast<std::size_t>(varint_len(type_bytes_ + k)) > k) ++k;
  return type_bytes_ + k;
}

Record& Record::add_int(std::int64_t v) {
  if (v == 0 || v == 1) return type(v == 0 ? 8 : 9);  // serial types 8 and 9 (schema format 4)
  const std::uint64_t u = v < 0 ? ~static_cast<std::uint64_t>(v) : static_cast<std::uint64_t>(v);
  int t, bytes;
  if (u <= 127) t = 1, bytes = 1;
  else if (u <= 32767) t = 2, bytes = 2;
  else if (u <= 8388607) t = 3, bytes = 3;
  else if (u <= 2147483647) t = 4, bytes = 4;
  else if (u <= 0x7FFFFFFFFFFFull) t = 5, bytes = 6;
  else t = 6, bytes = 8;
  type(static_cast<std::uint64_t>(t));
  // The low `bytes` bytes of v, most significant first.
  const std::uint64_t be = __builtin_bswap64(static_cast<std::uint64_t>(v) << (64 - 8 * bytes));
  char b[8];
  std::memcpy(b, &be, 8);
  body_.append(b, static_cast<std::size_t>(bytes));
  return *this;
}

Record& Record::add_real(double v) {
  type(7);
  const std::uint64_t be = __builtin_bswap64(std::bit_cast<std::uint64_t>(v));
  char b[8];
  std::memcpy(b, &be, 8);
  body_.append(b, 8);
  return *this;
}

Record& Record::add_real_or_null(double v) { return std::isfinite(v) ? add_real(v) : add_null(); }

Record& Record::add_blob(const void* data, std::size_t n) {
  type(12 + 2 * static_cast<std::uint64_t>(n));
  body_.append(static_cast<const char*>(data), n);
  return *this;
}

Record& Record::add_text(std::string_view s) {
  type(13 + 2 * static_cast<std::uint64_t>(s.size()));
  body_.append(s);
  return *this;
}

std::size_t Record::payload_size() const { return header_size() + body_.size(); }

std::size_t Record::cell_size() const {
  const std::size_t p = payload_size();
  return static_cast<std::size_t>(varint_len(p)) + static_cast<std::size_t>(varint_len(static_cast<std::uint64_t>(rowid_))) + p;
}

char* Record::write_cell(char* o) const {
  const std::size_t hs = header_size();
  o = put_varint(o, hs + body_.size());
  o = put_varint(o, static_cast<std::uint64_t>(rowid_));
  o = put_varint(o, hs);
  for (int i = 0; i < ntypes_; ++i) o = put_varint(o, types_[i]);
  std::memcpy(o, body_.data(), body_.size());
  return o + body_.size();
}

namespace {

// A page of a table's B-tree: a leaf holds rows [first, first + count), an interior node the
// nodes [first, first + count) of the level below; max_rowid is its subtree's largest rowid.
struct Node {
  std::size_t first = 0, count = 0;
  std::int64_t max_rowid = 0;
  std::uint32_t page = 0;
};

struct TablePlan {
  std::vector<Node> leaves;
  std::vector<std::vector<Node>> levels;  // interior levels, bottom up; the last has one node
};

class File {
 public:
  File(const std::string& file, const std::string& path) : path_(path) {
    fd_ = ::open(file.c_str(), O_RDWR | O_CLOEXEC);
    if (fd_ < 0) fail("cannot reopen the database file");
  }
  ~File() {
    if (fd_ >= 0) ::close(fd_);
  }
  void read(void* buf, std::size_t n, std::uint64_t off) const {
    auto* p = static_cast<char*>(buf);
    while (n > 0) {
      const ssize_t r = ::pread(fd_, p, n, static_cast<off_t>(off));
      if (r <= 0) fail(r == 0 ? "the database file is shorter than its header says" : "cannot read the database file");
      p += r, n -= static_cast<std::size_t>(r), off += static_cast<std::uint64_t>(r);
    }
  }
  void write(const void* buf, std::size_t n, std::uint64_t off) const {
    const auto* p = static_cast<const char*>(buf);
    while (n > 0) {
      const ssize_t r = ::pwrite(fd_, p, n, static_cast<off_t>(off));
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0) fail("cannot write the database file");
      p += r, n -= static_cast<std::size_t>(r), off += static_cast<std::uint64_t>(r);
    }
  }
  void close() {
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail("cannot close the database file");
  }
  [[noreturn]] void fail(const std::string& what) const {
    const int e = errno;
    fail_output(path_, what + (e ? std::string(": ") + std::strerror(e) : std::string()));
  }

 private:
  std::string path_;
  int fd_ = -1;
};

// Runs work(slot, i) for i in [0, n) in increasing order of claims, on two threads when
// allowed (slot 0: the calling thread, 1: the other).
template <class Work>
void claim_all(std::size_t n, bool two, Work work) {
  std::atomic<std::size_t> next{0};
  auto loop = [&](int slot) {
    for (std::size_t i; (i = next.fetch_add(1)) < n;) work(slot, i);
  };
  if (two && max_threads() > 1 && n > 1) run_beside([&] { loop(1); }, [&] { loop(0); });
  else loop(0);
}

}  // namespace

void write_bulk_tables(const std::string& file, const std::string& path, const std::vector<BulkTable>& tables,
                       std::uint64_t pending_byte) {
  File f(file, path);
  unsigned char hdr[100];
  f.read(hdr, sizeof hdr, 0);
  if (std::memcmp(hdr, "SQLite format 3", 16) != 0) fail_output(path, "internal: not an SQLite database");
  const std::uint64_t page_size = get_be(hdr + 16, 2) == 1 ? 65536 : get_be(hdr + 16, 2);
  const std::size_t usable = static_cast<std::size_t>(page_size - hdr[20]);
  if (hdr[18] != 1 || hdr[19] != 1 || get_be(hdr + 52, 4) != 0 || get_be(hdr + 44, 4) < 4 || get_be(hdr + 56, 4) != 1 ||
      get_be(hdr + 24, 4) != get_be(hdr + 92, 4))
    fail_output(path, "internal: the database is not in the layout the bulk writer expects (rollback journal, no "
                      "auto-vacuum, schema format 4, UTF-8, valid page count)");
  std::uint64_t pages = get_be(hdr + 28, 4);
  const std::uint64_t lock_page = pending_byte / page_size + 1;
  // A cell must fit in a leaf without overflow pages (payload at most usable - 35).
  const std::size_t max_payload = usable - 35;
  std::vector<TablePlan> plans(tables.size());
  auto new_page = [&] {
    if (++pages == lock_page) ++pages;
    if (pages > 0xFFFFFFFEull) fail_output(path, "the GeoPackage would exceed SQLite's largest page count");
    return static_cast<std::uint32_t>(pages);
  };

  // 1. The leaves, in chunks of rows packed and written by both threads: a chunk's rows are
  // packed into leaf pages in a buffer, then numbered once the chunk before it is (the chunks'
  // leaves take consecutive pages in chunk order), then written. A chunk starts a leaf of its
  // own, so the pages do not depend on the thread count; a chunk holds about kChunkBytes of
  // cells (by the size of its table's first row), so at most one partly filled leaf per
  // kChunkBytes.
  struct Chunk {
    std::size_t table, first, end;
    std::vector<Node> leaves;
  };
  std::vector<Chunk> chunks;
  for (std::size_t k = 0; k < tables.size(); ++k) {
    const BulkTable& t = tables[k];
    if (t.rows == 0) continue;
    Record rec;
    rec.clear(0);
    t.row(0, rec);
    const std::size_t per_chunk = std::max<std::size_t>(1024, kChunkBytes / (rec.cell_size() + 2));
    for (std::size_t r = 0; r < t.rows; r += per_chunk) chunks.push_back({k, r, std::min(t.rows, r + per_chunk), {}});
  }
  std::mutex mu;
  std::condition_variable cv;
  std::size_t numbered = 0;  // chunks whose leaves have page numbers
  std::exception_ptr failed;
  auto number = [&](std::size_t c) {  // after chunk c - 1 (in order)
    Chunk& ch = chunks[c];
    const bool alone = (c == 0 || chunks[c - 1].table != ch.table) && ch.end == tables[ch.table].rows;
    if (alone && ch.leaves.size() == 1) ch.leaves[0].page = static_cast<std::uint32_t>(tables[ch.table].root);
    else
      for (Node& l : ch.leaves) l.page = new_page();
  };
  // Both threads' page buffers from this thread's heap (which may hold pages freed before).
  std::string bufs[2];
  for (std::string& b : bufs) b.reserve(kChunkBytes + kChunkBytes / 4 + 2 * page_size);
  Record recs[2];
  bool two = true;
  for (const BulkTable& t : tables) two = two && t.thread_safe;
  claim_all(chunks.size(), two, [&](int slot, std::size_t c) {
    Chunk& ch = chunks[c];
    const BulkTable& t = tables[ch.table];
    std::string& buf = bufs[slot];
    Record& rec = recs[slot];
    std::size_t npages = 0, top = 0, cells = 0;
    std::int64_t last = 0;
    auto close_leaf = [&] {
      char* page = buf.data() + (npages - 1) * page_size;
      page[0] = 0x0D;
      put_be(page + 3, cells, 2);
      put_be(page + 5, top == 65536 ? 0 : top, 2);
    };
    try {
      for (std::size_t i = ch.first; i < ch.end; ++i) {
        rec.clear(0);
        t.row(i, rec);
        if (rec.payload_size() > max_payload)
          fail_output(path, "internal: a row of table '" + t.name + "' is too large for one page");
        if (i > ch.first && rec.rowid() <= last) fail_output(path, "internal: rowids of table '" + t.name + "' do not ascend");
        last = rec.rowid();
        const std::size_t cs = rec.cell_size();
        if (npages == 0 || 8 + 2 * (cells + 1) + cs > top) {
          if (npages > 0) close_leaf();
          ++npages;
          if (buf.size() < npages * page_size) buf.resize(npages * page_size);
          std::memset(buf.data() + (npages - 1) * page_size, 0, page_size);
          top = usable;
          cells = 0;
          ch.leaves.push_back({i, 0, 0, 0});
        }
        char* page = buf.data() + (npages - 1) * page_size;
        top -= cs;
        rec.write_cell(page + top);
        put_be(page + 8 + 2 * cells, top, 2);
        ++cells;
        ch.leaves.back().count++;
        ch.leaves.back().max_rowid = last;
      }
      close_leaf();
    } catch (...) {
      std::lock_guard<std::mutex> lock(mu);
      if (!failed) failed = std::current_exception();
    }
    {
      std::unique_lock<std::mutex> lock(mu);
      cv.wait(lock, [&] { return numbered == c; });  // the chunks before are numbered (or failed)
      if (!failed) {
        try {
          number(c);
        } catch (...) {
          failed = std::current_exception();
        }
      }
      ++numbered;
      cv.notify_all();
      if (failed) return;
    }
    // Consecutive pages in one write (a chunk's are consecutive but around the lock-byte page).
    const std::vector<Node>& leaves = ch.leaves;
    for (std::size_t j = 0; j < leaves.size();) {
      std::size_t e = j + 1;
      while (e < leaves.size() && leaves[e].page == leaves[e - 1].page + 1) ++e;
      f.write(buf.data() + j * page_size, (e - j) * page_size, (leaves[j].page - 1) * page_size);
      j = e;
    }
  });
  if (failed) std::rethrow_exception(failed);
  for (Chunk& ch : chunks) {
    auto& l = plans[ch.table].leaves;
    if (!l.empty() && ch.leaves.front().max_rowid <= l.back().max_rowid)
      fail_output(path, "internal: rowids of table '" + tables[ch.table].name + "' do not ascend");
    l.insert(l.end(), ch.leaves.begin(), ch.leaves.end());
  }
  chunks.clear();

  // 2. Interior levels on new pages, the top node on the root page.
  for (std::size_t k = 0; k < tables.size(); ++k) {
    TablePlan& p = plans[k];
    if (p.leaves.size() < 2) continue;  // none, or a leaf on the root page
    // Group the children of one level under parents, as many as fit in a page each.
    std::vector<std::int64_t> keys;
    for (const Node& l : p.leaves) keys.push_back(l.max_rowid);
    while (keys.size() > 1) {
      std::vector<Node> level;
      std::size_t used = usable;
      for (std::size_t i = 0; i < keys.size(); ++i) {
        // A child costs a cell (4-byte page + varint key) and its pointer, except the page's
        // last (the right-most pointer in the header): counted as a cell, so a page is never
        // over-full whichever child ends it.
        const std::size_t need = 4 + static_cast<std::size_t>(varint_len(static_cast<std::uint64_t>(keys[i]))) + 2;
        if (used + need > usable) {
          level.push_back({i, 0, 0, 0});
          used = 12;
        }
        used += need;
        level.back().count++;
        level.back().max_rowid = keys[i];
      }
      // No interior page with a single child (no cell): the last one takes one from the one before.
      if (level.size() > 1 && level.back().count == 1) {
        Node& prev = level[level.size() - 2];
        --prev.count;
        prev.max_rowid = keys[prev.first + prev.count - 1];
        --level.back().first;
        ++level.back().count;
      }
      keys.clear();
      for (const Node& n : level) keys.push_back(n.max_rowid);
      p.levels.push_back(std::move(level));
    }
    for (std::size_t d = 0; d < p.levels.size(); ++d)
      for (Node& n : p.levels[d]) n.page = d + 1 == p.levels.size() ? static_cast<std::uint32_t>(tables[k].root) : new_page();
  }

  // 4. The interior pages (few: hundreds of children each).
  std::string page(page_size, '\0');
  for (std::size_t k = 0; k < tables.size(); ++k) {
    const TablePlan& p = plans[k];
    for (std::size_t d = 0; d < p.levels.size(); ++d)
      for (const Node& n : p.levels[d]) {
        std::fill(page.begin(), page.end(), '\0');
        const std::vector<Node>& below = d == 0 ? p.leaves : p.levels[d - 1];
        std::size_t top = usable;
        const std::size_t cells = n.count - 1;
        for (std::size_t c = 0; c < cells; ++c) {
          const std::uint32_t pg = below[n.first + c].page;
          const std::int64_t key = below[n.first + c].max_rowid;
          char cell[13];
          put_be(cell, pg, 4);
          const std::size_t len = static_cast<std::size_t>(put_varint(cell + 4, static_cast<std::uint64_t>(key)) - cell);
          top -= len;
          std::memcpy(page.data() + top, cell, len);
          put_be(page.data() + 12 + 2 * c, top, 2);
        }
        if (12 + 2 * cells > top) fail_output(path, "internal: an interior page of table '" + tables[k].name + "' overflows");
        page[0] = 0x05;
        put_be(page.data() + 3, cells, 2);
        put_be(page.data() + 5, top == 65536 ? 0 : top, 2);
        put_be(page.data() + 8, below[n.first + n.count - 1].page, 4);
        f.write(page.data(), page_size, (n.page - 1) * page_size);
      }
  }

  // 5. The header: the new page count, trusted (change counter = version-valid-for).
  const std::uint64_t counter = (get_be(hdr + 24, 4) + 1) & 0xFFFFFFFFull;
  char h[4];
  put_be(h, counter, 4);
  f.write(h, 4, 24);
  f.write(h, 4, 92);
  put_be(h, pages, 4);
  f.write(h, 4, 28);
  // The file ends with the last page (it does unless the lock-byte page was the last one taken).
  f.close();
}

}  // namespace fdr::io::detail
