#pragma once
// InflateAhead: a zlib or gzip stream inflated on a thread of its own, ahead
// of the reader that converts what comes out. A 25 µm volume's gzip NRRD
// (1024 x 1024 x 704 floats) took 5.4-5.9 s on one core, about half of it in
// zlib (inflate and the gzip CRC) and half turning bytes into densities and
// the grid; overlapped, a second core takes zlib's half. The reader works in
// bursts (VolumeBuilder puts eight slices into the grid at once), so the
// look-ahead must cover one: with 4 MiB ahead that read took 5.1 s, with one
// slab (32 MiB) 2.9-3.6 s, with two or three no less. It never holds more than
// `aheadBytes`: a stream that inflates beyond what the reader wants costs no
// more memory, since the reader stops and the destructor stops the thread.
// Buffers are made when first filled, so a small file costs one or two.
//
//   InflateAhead ahead(file, 15 + 32, 32 << 20);  // reads `file` from where it stands
//   for (InflateAhead::Chunk c = ahead.next(); c.size > 0; c = ahead.next()) use(c.data, c.size);
//   if (ahead.end() != InflateAhead::End::Complete) ...  // ahead.message()
#include <condition_variable>
#include <cstddef>
#include <istream>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

struct z_stream_s;  // zlib's z_stream, kept out of this header

namespace millsim {

class InflateAhead {
public:
  // How the stream ended, once next() has returned an empty chunk.
  enum class End {
    Complete,   // the stream's end marker (and, for gzip, its CRC and length) was read
    Corrupt,    // zlib refused the data: message() says why
    Truncated,  // the input ran out before the stream's end
  };
  struct Chunk {
    const unsigned char* data = nullptr;
    std::size_t size = 0;
  };

  static constexpr std::size_t kChunkBytes = std::size_t(1) << 20;

  // Starts inflating `in` from its current position; `windowBits` as for
  // zlib's inflateInit2 (15 + 32: zlib or gzip, by the header); at most
  // `aheadBytes` (rounded up to whole chunks, at least two) inflated and not
  // yet handed back. `in` is read on the inflating thread only, until the
  // destructor. Throws std::runtime_error if zlib cannot start.
  InflateAhead(std::istream& in, int windowBits, std::size_t aheadBytes);
  ~InflateAhead();
  InflateAhead(const InflateAhead&) = delete;
  InflateAhead& operator=(const InflateAhead&) = delete;

  // The next inflated bytes, valid until the next call; size 0 once the stream
  // has ended. Blocks while the inflating thread is behind.
  Chunk next();
  End end() const { return end_; }
  const std::string& message() const { return message_; }

private:
  // The inflating thread's loop: fills the ring until the stream ends or the reader stops.
  void inflateAll(std::istream& in);
  struct ZStreamDelete {
    void operator()(z_stream_s* zs) const;
  };

  const int chunks_;
  std::vector<std::vector<unsigned char>> buffers_;
  std::vector<std::size_t> sizes_;
  // Guarded by mutex_: the chunks filled and not yet handed back, a ring from `first_`;
  // whether the inflating thread is done; whether the reader wants it to stop.
  std::mutex mutex_;
  std::condition_variable changed_;
  int first_ = 0, filled_ = 0;
  bool done_ = false, stop_ = false;
  // The chunk the reader holds (first_, handed back at its next call), or -1.
  // It still counts as filled, so the inflating thread leaves it alone.
  int held_ = -1;
  End end_ = End::Complete;  // written by the inflating thread before done_
  std::string message_;
  std::unique_ptr<z_stream_s, ZStreamDelete> zs_;  // used by the inflating thread only, once started
  std::thread thread_;
};

}  // namespace millsim
