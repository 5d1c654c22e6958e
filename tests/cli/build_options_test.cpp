// Every build option of every traversal unit (golden/unit.h, BuildOption) on
// every command that takes it: `lancer run`, and `lancer render` and `lancer
// trace` for the options that shape the float structure. A value below the
// option's rule or above its largest is refused before anything runs, in one
// line naming the flag, with exit status 1; the smallest valid value runs (and
// on `lancer run` the largest). A new unit's options are covered with no edit here.
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "golden/units.h"
#include "ref/accel.h"

namespace lancer::test {
namespace {

constexpr int kNoLimit = std::numeric_limits<int>::max();

struct OptionUse {
  std::string command;  // run, render, trace
  std::string unit;     // its --accel
  std::string flag;
  int least;  // 1 for a positive option, else 0
  int max;    // kNoLimit: none
};

// The test's name in ctest: "run --grid-res".
void PrintTo(const OptionUse& use, std::ostream* out) { *out << use.command << " " << use.flag; }

// Each option as `lancer run` takes it (the unit's largest) and, where it shapes
// the float structure, as render and trace do (the float structure's largest,
// as sw/cli/options.cpp's AccelArgs takes it).
std::vector<OptionUse> everyOptionUse() {
  std::vector<OptionUse> uses;
  fx::forEachTraversalUnit([&](auto unit) {
    const std::string name = decltype(unit)::kNames.unit;
    for (const fx::BuildOption& o : decltype(unit)::buildOptions()) {
      const int least = o.positive ? 1 : 0;
      uses.push_back({"run", name, o.flag, least, o.max});
      if (!o.shapesReference) continue;
      const ReferenceBuildOption* reference = findReferenceBuildOption(o.field);
      for (const char* command : {"render", "trace"}) {
        uses.push_back({command, name, o.flag, least, reference ? reference->max : o.max});
      }
    }
  });
  return uses;
}

std::string quoted(const std::string& word) {
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

struct Outcome {
  int status;  // the exit status; 128 + the signal if one ended it
  std::vector<std::string> errorLines;
};

// `lancer` on a 4x4 camera with `flag value`, writing into the test's own files.
Outcome runWith(const OptionUse& use, int value) {
  const std::string out = fmt::format("{}/build_option_{}_{}", LANCER_CLI_OUT, use.command, use.flag.substr(2));
  std::vector<std::string> args{LANCER_BINARY, use.command, "--accel", use.unit, "--width", "4", "--height", "4",
                                use.flag, std::to_string(value)};
  if (use.command == "run") args.insert(args.end(), {"--model", "golden", "--effects", "primary"});
  if (use.command == "render") args.insert(args.end(), {"--out", out + ".png"});
  if (use.command == "trace") args.insert(args.end(), {"--hits", out + ".csv"});
  std::string line;
  for (const std::string& a : args) line += quoted(a) + " ";
  const int status = std::system((line + ">/dev/null 2>" + quoted(out + ".err")).c_str());
  Outcome outcome{WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), {}};
  std::ifstream err(out + ".err");
  for (std::string text; std::getline(err, text);) outcome.errorLines.push_back(text);
  return outcome;
}

class BuildOptionTest : public ::testing::TestWithParam<OptionUse> {};

TEST_P(BuildOptionTest, RefusesValuesOutOfRangeAndTakesItsBounds) {
  const OptionUse& use = GetParam();
  std::vector<int> refused{use.least - 1};
  if (use.max != kNoLimit) refused.push_back(use.max + 1);
  for (int value : refused) {
    const Outcome o = runWith(use, value);
    const std::string said = ::testing::PrintToString(o.errorLines);
    EXPECT_EQ(o.status, 1) << use.flag << " " << value << ": " << said;
    ASSERT_EQ(o.errorLines.size(), 1u) << use.flag << " " << value << ": " << said;
    EXPECT_NE(o.errorLines[0].find(fmt::format("{} {}", use.flag, value)), std::string::npos) << said;
  }
  // The largest only on the hardware's image: the float grid's 1024 voxels a
  // side take gigabytes.
  std::vector<int> taken{use.least};
  if (use.command == "run" && use.max != kNoLimit) taken.push_back(use.max);
  for (int value : taken) {
    const Outcome o = runWith(use, value);
    EXPECT_EQ(o.status, 0) << use.flag << " " << value << ": " << ::testing::PrintToString(o.errorLines);
  }
}

INSTANTIATE_TEST_SUITE_P(EveryUnit, BuildOptionTest, ::testing::ValuesIn(everyOptionUse()),
                         [](const ::testing::TestParamInfo<OptionUse>& info) {
                           std::string name = info.param.command + "_" + info.param.flag.substr(2);
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

}  // namespace
}  // namespace lancer::test
