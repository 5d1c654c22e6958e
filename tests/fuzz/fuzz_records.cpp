// libFuzzer target: the record unpacking (sw/golden/records). The first input
// byte picks a record of allRecords(), the rest are its wire words (zero-padded).
// Every value unpackFields returns lies in its field's range (unsigned: below
// 2^width; signed: sign-extended from width bits), and packFields puts back
// exactly the record's bits of the input. For isect_ray_t, isect_tri_t and
// isect_res_t the typed forms (unpackRay, unpackTriangle, unpackResult) agree
// with unpackFields and packWire round-trips them the same way.

#include <vector>

#include "fuzz_support.h"
#include "golden/records.h"
#include "golden/units.h"

using namespace lancer;
using namespace lancer::fx;

namespace {

// The input words with the bits above the record cleared: what a pack must give back.
Wire recordBitsOf(const Wire& words, int bits) {
  Wire out(words.begin(), words.begin() + wireWords(bits));
  if (bits % 32) out.back() &= (uint32_t(1) << (bits % 32)) - 1;
  return out;
}

std::string hex(const Wire& w) {
  std::string s;
  for (size_t i = w.size(); i-- > 0;) s += fmt::format("{:08x}", w[i]);
  return s;
}

void checkRanges(const RecordSpec& spec, const std::vector<u128>& values) {
  size_t at = 0;
  for (const FieldSpec& f : spec.fields) {
    for (int e = 0; e < f.count; ++e, ++at) {
      const u128 v = values[at];
      const u128 low = f.width >= 128 ? ~u128(0) : (u128(1) << f.width) - 1;
      if (!f.isSigned) {
        FUZZ_CHECK((v & ~low) == 0, "{}.{}[{}]: unsigned value above {} bits", spec.name, f.name, e, f.width);
      } else {
        const bool negative = (v >> (f.width - 1)) & 1;
        const u128 high = v & ~low;
        FUZZ_CHECK(high == (negative ? ~low : 0), "{}.{}[{}]: not sign-extended from {} bits", spec.name, f.name,
                   e, f.width);
      }
    }
  }
}

template <class Record>
void checkTyped(const RecordSpec& spec, void (*unpack)(std::span<const uint32_t>, Record&), const Wire& words,
                const std::vector<u128>& values, const Wire& expected) {
  Record record;
  unpack(words, record);
  const auto typed = fieldArray(record);
  FUZZ_CHECK(std::equal(typed.begin(), typed.end(), values.begin(), values.end()),
             "{}: the typed unpack disagrees with unpackFields on {}", spec.name, hex(words));
  const Wire packed = packWire(record);
  FUZZ_CHECK(packed == expected, "{}: {} -> packWire -> {}", spec.name, hex(expected), hex(packed));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  fuzz::Bytes in(data, size);
  const std::vector<RecordSpec>& all = allRecords();
  const RecordSpec& spec = all[in.take<uint8_t>() % all.size()];
  const int bits = recordBits(spec.fields);
  // At least the record's words; any extra words must be ignored.
  Wire words(std::max<size_t>(size_t(wireWords(bits)), (in.left() + 3) / 4));
  for (uint32_t& w : words) w = in.take<uint32_t>();
  const std::vector<u128> values = unpackFields(spec.fields, words);
  FUZZ_CHECK(values.size() == valueCount(spec.fields), "{}: {} values", spec.name, values.size());
  checkRanges(spec, values);
  const Wire expected = recordBitsOf(words, bits);
  const Wire packed = packFields(spec.fields, values);
  FUZZ_CHECK(packed == expected, "{}: {} -> unpack -> pack -> {}", spec.name, hex(expected), hex(packed));

  if (&spec == &all[0]) checkTyped<QRay>(spec, unpackRay, words, values, expected);
  if (&spec == &all[1]) checkTyped<QTriangle>(spec, unpackTriangle, words, values, expected);
  if (&spec == &all[2]) checkTyped<IsectResult>(spec, unpackResult, words, values, expected);
  return 0;
}
