#pragma once

// Decimals that a reader which does not round correctly gets wrong, shared by
// the tests of the number parser and of every text format that uses it
// (text_test.cpp, obj_test.cpp, ply_test.cpp).

#include <string>
#include <vector>

namespace lancer::test {

// Finite float coordinates at the ends of float's range, at 2^+-60 (a scaled
// scene) and of full precision; strtof is the expectation.
inline const std::vector<std::string> kExtremeDecimals{
    "1e-38",                      // below the smallest normal, 2^-126
    "1.17549435e-38",             // 2^-126
    "1.1754942e-38",              // the largest subnormal
    "1e-40",                      // a subnormal
    "1e-45",                      // the smallest subnormal, 2^-149
    "1.401298464324817e-45",      // 2^-149 to 16 digits
    "2.8e-45",                    // 2 * 2^-149
    "7.006492321624086e-46",      // just above half of 2^-149: rounds up to it
    "3.4e38",                     // near the largest float
    "3.4028235e38",               // the largest float
    "-3.4028234663852886e38",     // the largest float, negative, to 17 digits
    "8.67361737988403547205962240695953369140625e-19",  // 2^-60 exactly
    "8.673617379884035e-19",      // 2^-60 to 16 digits
    "1152921504606846976",        // 2^60
    "1.152921504606847e18",       // 2^60 to 16 digits
    "-2.710505431213761e-20",     // -2^-65
    "3.1377567211166024e-10",     // issue 21's coordinate: 0x1.59p-32
    "123456789012345678901234567890",
    "0.1",
    "-0.0",
};

// A decimal at, or a hair from, the midpoint of two adjacent floats, and the
// float it rounds to (ties to even).
struct Halfway {
  const char* text;
  const char* nearest;  // as fmt's {:a} prints it
};

inline const std::vector<Halfway> kHalfwayDecimals{
    {"1.000000059604644775390625", "0x1p+0"},              // 1 + 2^-24: between 1 and 1 + 2^-23, to even
    {"1.00000005960464477539062500001", "0x1.000002p+0"},  // a hair above: up
    {"1.00000005960464477539062499999", "0x1p+0"},         // a hair below: down
    {"1.0000000596046447753906250000001", "0x1.000002p+0"},  // above by less than a double can tell
    {"1.000000178813934326171875", "0x1.000004p+0"},       // 1 + 3 * 2^-24: between odd and even, to even
    {"-1.000000059604644775390625", "-0x1p+0"},
    {"16777217", "0x1p+24"},                               // 2^24 + 1, to even 2^24
    {"16777219", "0x1.000004p+24"},                        // 2^24 + 3, to even 2^24 + 4
    // 1.5 * 2^-149: between the two smallest subnormals, to even 2^-148.
    {"2.101947696487225606385594374934874196920392912814773657635602425834686624028790902229957282543182373046875e-45",
     "0x1p-148"},
    // Half of 2^-149: to even, zero; a hair above: 2^-149.
    {"7.00649232162408535461864791644958065640130970938257885878534141944895541342930300743319094181060791015625e-46",
     "0x0p+0"},
    {"7.006492321624085354618647916449580656401309709382578858785341419448955413429303007433190941810607910156251e-46",
     "0x1p-149"},
};

}  // namespace lancer::test
