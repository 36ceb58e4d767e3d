// zlib/deflate compressor after RFC 1950 (zlib format) and RFC 1951 (deflate): greedy LZ77 over a
// 32 KiB window (hash chains of 3-byte prefixes, as zlib does) coded with the fixed Huffman tables
// of RFC 1951 §3.2.6; or stored blocks (§3.2.4). CRC-32 as specified for PNG (ISO 3309).
#include "treesketch/render/deflate.h"

#include <algorithm>
#include <array>

namespace treesketch::render {

namespace {

constexpr std::size_t kWindow = 32768;
constexpr std::size_t kMinMatch = 3;
constexpr std::size_t kMaxMatch = 258;
constexpr int kHashBits = 15;

// RFC 1951 §3.2.5: length codes 257..285 and distance codes 0..29 (base value, extra bits).
constexpr std::array<std::uint16_t, 29> kLengthBase = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                                       31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr std::array<std::uint8_t, 29> kLengthExtra = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                                       2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
constexpr std::array<std::uint16_t, 30> kDistBase = {1,    2,    3,    4,    5,    7,    9,    13,    17,    25,
                                                     33,   49,   65,   97,   129,  193,  257,  385,   513,   769,
                                                     1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
constexpr std::array<std::uint8_t, 30> kDistExtra = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                                                     6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

std::array<std::uint32_t, 256> makeCrcTable() {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[i] = c;
  }
  return t;
}

/// Writes bits least-significant first into a byte vector, as deflate packs them.
class BitWriter {
 public:
  explicit BitWriter(std::vector<std::uint8_t>& out) : out_(out) {}
  void bits(std::uint32_t value, int count) {
    acc_ |= static_cast<std::uint64_t>(value) << used_;
    used_ += count;
    while (used_ >= 8) {
      out_.push_back(static_cast<std::uint8_t>(acc_));
      acc_ >>= 8;
      used_ -= 8;
    }
  }
  /// A Huffman code: its bits go most-significant first.
  void code(std::uint32_t code, int length) {
    std::uint32_t rev = 0;
    for (int i = 0; i < length; ++i) rev |= ((code >> i) & 1u) << (length - 1 - i);
    bits(rev, length);
  }
  void alignToByte() {
    if (used_ > 0) bits(0, 8 - used_);
  }

 private:
  std::vector<std::uint8_t>& out_;
  std::uint64_t acc_ = 0;
  int used_ = 0;
};

/// Fixed Huffman literal/length code of symbol 0..287 (RFC 1951 §3.2.6).
void writeFixedSymbol(BitWriter& w, int sym) {
  if (sym < 144)
    w.code(0x30 + sym, 8);
  else if (sym < 256)
    w.code(0x190 + (sym - 144), 9);
  else if (sym < 280)
    w.code(sym - 256, 7);
  else
    w.code(0xC0 + (sym - 280), 8);
}

void writeMatch(BitWriter& w, std::size_t length, std::size_t distance) {
  int li = static_cast<int>(std::upper_bound(kLengthBase.begin(), kLengthBase.end(), length) - kLengthBase.begin()) - 1;
  writeFixedSymbol(w, 257 + li);
  if (kLengthExtra[li]) w.bits(static_cast<std::uint32_t>(length - kLengthBase[li]), kLengthExtra[li]);
  int di = static_cast<int>(std::upper_bound(kDistBase.begin(), kDistBase.end(), distance) - kDistBase.begin()) - 1;
  w.code(static_cast<std::uint32_t>(di), 5);
  if (kDistExtra[di]) w.bits(static_cast<std::uint32_t>(distance - kDistBase[di]), kDistExtra[di]);
}

std::uint32_t hash3(const std::uint8_t* p) {
  std::uint32_t v = (static_cast<std::uint32_t>(p[0]) << 16) | (static_cast<std::uint32_t>(p[1]) << 8) | p[2];
  return (v * 2654435761u) >> (32 - kHashBits);
}

void deflateFixed(const std::uint8_t* data, std::size_t n, const DeflateOptions& opt, BitWriter& w) {
  w.bits(1, 1);  // BFINAL
  w.bits(1, 2);  // BTYPE = 01, fixed Huffman
  std::vector<std::int64_t> head(std::size_t(1) << kHashBits, -1);
  std::vector<std::int64_t> prev(kWindow, -1);
  const std::size_t maxChain = static_cast<std::size_t>(std::max(1, opt.maxChainLength));
  const std::size_t nice =
      std::clamp<std::size_t>(static_cast<std::size_t>(std::max(opt.niceLength, 3)), kMinMatch, kMaxMatch);
  auto insert = [&](std::size_t pos) {
    if (pos + kMinMatch > n) return;
    std::uint32_t h = hash3(data + pos);
    prev[pos & (kWindow - 1)] = head[h];
    head[h] = static_cast<std::int64_t>(pos);
  };
  std::size_t pos = 0;
  while (pos < n) {
    std::size_t bestLen = 0, bestDist = 0;
    if (pos + kMinMatch <= n) {
      const std::size_t maxLen = std::min(kMaxMatch, n - pos);
      std::int64_t cand = head[hash3(data + pos)];
      for (std::size_t chain = 0; cand >= 0 && chain < maxChain; ++chain) {
        std::size_t c = static_cast<std::size_t>(cand);
        if (pos - c > kWindow) break;
        std::size_t len = 0;
        while (len < maxLen && data[c + len] == data[pos + len]) ++len;
        if (len > bestLen) {
          bestLen = len;
          bestDist = pos - c;
          if (len >= nice) break;
        }
        std::int64_t next = prev[c & (kWindow - 1)];
        if (next >= cand) break;  // a slot reused by a newer position: the chain ends here
        cand = next;
      }
    }
    if (bestLen >= kMinMatch) {
      writeMatch(w, bestLen, bestDist);
      for (std::size_t i = 0; i < bestLen; ++i) insert(pos + i);
      pos += bestLen;
    } else {
      writeFixedSymbol(w, data[pos]);
      insert(pos);
      ++pos;
    }
  }
  writeFixedSymbol(w, 256);  // end of block
  w.alignToByte();
}

void deflateStored(const std::uint8_t* data, std::size_t n, std::vector<std::uint8_t>& out) {
  std::size_t pos = 0;
  do {
    std::size_t len = std::min<std::size_t>(65535, n - pos);
    bool last = pos + len == n;
    out.push_back(last ? 1 : 0);  // BFINAL, BTYPE = 00, then padding to the byte boundary
    out.push_back(static_cast<std::uint8_t>(len & 0xFF));
    out.push_back(static_cast<std::uint8_t>(len >> 8));
    out.push_back(static_cast<std::uint8_t>(~len & 0xFF));
    out.push_back(static_cast<std::uint8_t>((~len >> 8) & 0xFF));
    out.insert(out.end(), data + pos, data + pos + len);
    pos += len;
  } while (pos < n);
}

}  // namespace

std::uint32_t crc32(const std::uint8_t* data, std::size_t n, std::uint32_t crc) {
  static const std::array<std::uint32_t, 256> table = makeCrcTable();
  std::uint32_t c = ~crc;
  for (std::size_t i = 0; i < n; ++i) c = table[(c ^ data[i]) & 0xFF] ^ (c >> 8);
  return ~c;
}

std::uint32_t adler32(const std::uint8_t* data, std::size_t n, std::uint32_t adler) {
  constexpr std::uint32_t kMod = 65521;
  std::uint32_t a = adler & 0xFFFF, b = adler >> 16;
  while (n > 0) {
    std::size_t chunk = std::min<std::size_t>(n, 5552);  // largest run with no 32-bit overflow (zlib's NMAX)
    for (std::size_t i = 0; i < chunk; ++i) {
      a += data[i];
      b += a;
    }
    a %= kMod;
    b %= kMod;
    data += chunk;
    n -= chunk;
  }
  return (b << 16) | a;
}

std::vector<std::uint8_t> zlibCompress(const std::uint8_t* data, std::size_t n, const DeflateOptions& options) {
  std::vector<std::uint8_t> out;
  out.reserve(options.compress ? n / 4 + 64 : n + n / 65535 * 5 + 16);
  out.push_back(0x78);                            // CM = 8 (deflate), CINFO = 7 (32 KiB window)
  out.push_back(options.compress ? 0x9C : 0x01);  // FCHECK makes the header a multiple of 31
  if (options.compress) {
    BitWriter w(out);
    deflateFixed(data, n, options, w);
  } else {
    deflateStored(data, n, out);
  }
  std::uint32_t a = adler32(data, n);
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(a >> shift));
  return out;
}

}  // namespace treesketch::render
