#include "model/io.hpp"

#include <lzma.h>
#include <time.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace masonry {

std::optional<std::string> read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

namespace {

std::string xz_decompress(const std::string& data, const std::string& path) {
  lzma_stream z = LZMA_STREAM_INIT;
  if (lzma_stream_decoder(&z, UINT64_MAX, LZMA_CONCATENATED) != LZMA_OK) throw std::runtime_error(path + ": cannot start the xz decoder");
  std::string out;
  char buf[1 << 16];
  z.next_in = reinterpret_cast<const uint8_t*>(data.data());
  z.avail_in = data.size();
  lzma_ret ret = LZMA_OK;
  while (ret == LZMA_OK) {
    z.next_out = reinterpret_cast<uint8_t*>(buf);
    z.avail_out = sizeof buf;
    ret = lzma_code(&z, LZMA_FINISH);
    out.append(buf, sizeof buf - z.avail_out);
  }
  lzma_end(&z);
  if (ret != LZMA_STREAM_END) throw std::runtime_error(path + ": not a valid xz file (liblzma error " + std::to_string(int(ret)) + ")");
  return out;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

std::optional<std::string> read_text_or_xz(const std::string& path) {
  if (ends_with(path, ".xz")) {
    const std::optional<std::string> packed = read_text(path);
    return packed ? std::optional<std::string>(xz_decompress(*packed, path)) : std::nullopt;
  }
  if (std::optional<std::string> text = read_text(path)) return text;
  if (const std::optional<std::string> packed = read_text(path + ".xz")) return xz_decompress(*packed, path + ".xz");
  return std::nullopt;
}

void write_file_atomic(const std::string& path, const std::string& text) {
  std::error_code ec_ignored;
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    // The reason from errno: a full disk, a missing permission, a read-only file system.
    if (!out) throw std::runtime_error(tmp + ": cannot write: " + std::strerror(errno));
    out << text;
    out.flush();
    if (!out) {
      const std::string why = std::strerror(errno);
      out.close();
      std::filesystem::remove(tmp, ec_ignored);
      throw std::runtime_error(tmp + ": write failed: " + why);
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error(path + ": cannot replace: " + ec.message());
}

double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace masonry
