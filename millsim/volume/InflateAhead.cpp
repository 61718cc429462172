#include "millsim/volume/InflateAhead.h"

#include <algorithm>
#include <stdexcept>

#include <zlib.h>

namespace millsim {

InflateAhead::InflateAhead(std::istream& in, int windowBits, std::size_t aheadBytes)
    : chunks_(int(std::clamp<std::size_t>((aheadBytes + kChunkBytes - 1) / kChunkBytes, 2, 1024))),
      buffers_(std::size_t(chunks_)), sizes_(std::size_t(chunks_)), zs_(new z_stream{}) {
  // zlib is started here, so that a failure to start is the constructor's error.
  if (inflateInit2(zs_.get(), windowBits) != Z_OK) throw std::runtime_error("cannot start zlib");
  thread_ = std::thread([this, &in] { inflateAll(in); });
}

// inflateEnd also on a stream whose inflateInit2 failed: zlib sees it never
// started and frees nothing.
void InflateAhead::ZStreamDelete::operator()(z_stream_s* zs) const {
  inflateEnd(zs);
  delete zs;
}

void InflateAhead::inflateAll(std::istream& in) {
  z_stream& zs = *zs_;
  std::vector<unsigned char> input(std::size_t(1) << 18);
  bool inputEnd = false;
  int next = 0;  // the buffer to fill next
  while (true) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      // `next` follows the filled ones in the ring: free while they are fewer than all.
      changed_.wait(lock, [&] { return stop_ || filled_ < chunks_; });
      if (stop_) return;
    }
    std::vector<unsigned char>& out = buffers_[std::size_t(next)];
    if (out.empty()) out.resize(kChunkBytes);  // on first use: a small file needs one or two
    zs.next_out = out.data();
    zs.avail_out = uInt(out.size());
    int rc = Z_OK;
    // Fill the buffer, or stop at the stream's end or an error.
    while (zs.avail_out > 0) {
      if (zs.avail_in == 0 && !inputEnd) {
        in.read(reinterpret_cast<char*>(input.data()), std::streamsize(input.size()));
        zs.next_in = input.data();
        zs.avail_in = uInt(in.gcount());
        if (zs.avail_in == 0) inputEnd = true;
      }
      rc = inflate(&zs, Z_NO_FLUSH);
      if (rc != Z_OK) break;
    }
    const std::size_t got = out.size() - zs.avail_out;
    const bool last = rc == Z_STREAM_END || rc == Z_DATA_ERROR || rc == Z_MEM_ERROR || rc == Z_NEED_DICT ||
                      rc == Z_STREAM_ERROR || (rc == Z_BUF_ERROR && inputEnd);
    if (last) {
      end_ = rc == Z_STREAM_END ? End::Complete : rc == Z_BUF_ERROR ? End::Truncated : End::Corrupt;
      if (end_ == End::Corrupt) message_ = zs.msg ? zs.msg : "zlib error";
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (got > 0) {
      sizes_[std::size_t(next)] = got;
      ++filled_;
      next = (next + 1) % chunks_;
    }
    if (last) done_ = true;
    changed_.notify_all();
    if (last) return;
  }
}

InflateAhead::~InflateAhead() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

InflateAhead::Chunk InflateAhead::next() {
  std::unique_lock<std::mutex> lock(mutex_);
  if (held_ >= 0) {
    // The chunk handed out last time is free again.
    held_ = -1;
    first_ = (first_ + 1) % chunks_;
    --filled_;
    changed_.notify_all();
  }
  changed_.wait(lock, [&] { return filled_ > 0 || done_; });
  if (filled_ == 0) return {};
  held_ = first_;
  return Chunk{buffers_[std::size_t(first_)].data(), sizes_[std::size_t(first_)]};
}

}  // namespace millsim
