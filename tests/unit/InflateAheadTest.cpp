// InflateAhead (issue 44, part 1): a gzip stream inflated on its own thread
// comes out whole and in order however small the look-ahead, says how it
// ended (complete, truncated, corrupt), and stops when the reader stops.
#include <gtest/gtest.h>

#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "ZlibCompress.h"
#include "millsim/volume/InflateAhead.h"

using namespace millsim;

namespace {

// 5.5 MiB that compress, but not to nothing: a counter's bytes mixed with a
// simple generator, so that a chunk out of order or twice is seen.
std::string original() {
  std::string s(5 * InflateAhead::kChunkBytes + InflateAhead::kChunkBytes / 2, '\0');
  std::uint32_t x = 12345;
  for (std::size_t i = 0; i < s.size(); ++i) {
    x = x * 1103515245u + 12345u;
    s[i] = char((i / 4096) ^ ((x >> 16) & 0x0f));
  }
  return s;
}

std::string gzip(const std::string& in) { return test::compress(in, 15 + 16); }

struct Read {
  std::string bytes;
  InflateAhead::End end;
  std::string message;
};

Read inflateAll(const std::string& compressed, std::size_t aheadBytes) {
  std::istringstream in(compressed);
  InflateAhead ahead(in, 15 + 32, aheadBytes);
  Read r;
  for (InflateAhead::Chunk c = ahead.next(); c.size > 0; c = ahead.next())
    r.bytes.append(reinterpret_cast<const char*>(c.data), c.size);
  r.end = ahead.end();
  r.message = ahead.message();
  return r;
}

}  // namespace

TEST(InflateAhead, AStreamComesOutWholeAndInOrderWhateverTheLookAhead) {
  const std::string data = original(), packed = gzip(data);
  ASSERT_LT(packed.size(), data.size());
  for (std::size_t ahead : {std::size_t(0), InflateAhead::kChunkBytes * 3, InflateAhead::kChunkBytes * 64}) {
    const Read r = inflateAll(packed, ahead);
    EXPECT_EQ(r.end, InflateAhead::End::Complete) << ahead;
    ASSERT_EQ(r.bytes.size(), data.size()) << ahead;
    EXPECT_TRUE(r.bytes == data) << "look-ahead " << ahead << " bytes: the chunks came out of order or twice";
  }
}

TEST(InflateAhead, SaysWhetherTheStreamWasCutShortOrCorrupt) {
  const std::string data = original(), packed = gzip(data);
  const Read cut = inflateAll(packed.substr(0, packed.size() / 2), InflateAhead::kChunkBytes * 2);
  EXPECT_EQ(cut.end, InflateAhead::End::Truncated);
  EXPECT_LT(cut.bytes.size(), data.size());
  EXPECT_TRUE(data.compare(0, cut.bytes.size(), cut.bytes) == 0) << "what came before the cut is the data";

  std::string bad = packed;
  for (std::size_t i = bad.size() / 3; i < bad.size() / 3 + 64; ++i) bad[i] = char(~bad[i]);
  const Read corrupt = inflateAll(bad, InflateAhead::kChunkBytes * 2);
  EXPECT_EQ(corrupt.end, InflateAhead::End::Corrupt);
  EXPECT_FALSE(corrupt.message.empty());

  std::string crc = packed;  // the gzip trailer: CRC-32, then the length
  crc[crc.size() - 8] = char(~crc[crc.size() - 8]);
  const Read checked = inflateAll(crc, InflateAhead::kChunkBytes * 2);
  EXPECT_EQ(checked.end, InflateAhead::End::Corrupt) << "the gzip CRC is checked";
  EXPECT_EQ(checked.message, "incorrect data check");
}

// A reader that stops early (a stream holding more than its header says)
// leaves the inflating thread blocked on a full look-ahead: the destructor
// must stop it rather than hang.
TEST(InflateAhead, AReaderThatStopsEarlyStopsTheThread) {
  const std::string packed = gzip(original());
  for (int taken : {0, 1, 2}) {
    std::istringstream in(packed);
    InflateAhead ahead(in, 15 + 32, InflateAhead::kChunkBytes * 2);
    for (int i = 0; i < taken; ++i) ASSERT_GT(ahead.next().size, 0u);
  }
  SUCCEED();
}
