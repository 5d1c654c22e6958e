// lancer_fst_activity: the toggle rates of an FST waveform's signals, for the
// silicon flow's power (scripts/silicon, docs/silicon.md "Power").
//
//   lancer_fst_activity WAVE.fst [WAVE.1.fst ...] [--clock NAME] > activity.json
//
// For every traced signal: its width, the bit transitions seen, and the
// transitions per bit per clock cycle (cycles = rising edges of the clock, by
// default the first signal named clk_i), summed over the waveforms given (an
// effects run writes one a job: driver/wave_file.h). Arrays and the bits of a vector are
// one entry: the name without its indices. The silicon flow sets these rates
// on the netlist's registers and inputs by name; OpenSTA propagates them
// through the logic.
//
// Verilator's FST writer includes GTKWave's reader (fstapi.c), so this needs
// nothing Verilator does not ship.

#include <cstdint>
#include <cstdio>
#include <algorithm>
#include <cstring>
#include <map>
#include <string>
#include <vector>

extern "C" {
#include "gtkwave/fstapi.h"
}

namespace {

struct Signal {
  std::string name;  // scope.path.name, indices dropped
  int width = 0;
  std::vector<char> last;  // previous value, one char a bit ('0', '1', 'x', 'z')
  bool seen = false;
  uint64_t toggles = 0;
};

struct Entry {
  uint64_t bits = 0;  // bits summed over the signals folded into the entry
  uint64_t toggles = 0;
};

struct State {
  std::vector<Signal> byHandle;  // indexed by FST handle (aliases share one)
  fstHandle clock = 0;
  uint64_t risingEdges = 0;
  char clockLast = '0';
  uint64_t firstTime = 0, lastTime = 0;
  bool anyTime = false;
};

// "a.b.c[3]" and "a.b.c(3)" name the same entry as "a.b.c".
std::string baseName(std::string name) {
  for (;;) {
    const size_t n = name.size();
    if (n && (name[n - 1] == ']' || name[n - 1] == ')')) {
      const size_t open = name.find_last_of(name[n - 1] == ']' ? '[' : '(');
      if (open == std::string::npos) break;
      name.erase(open);
      while (!name.empty() && name.back() == ' ') name.pop_back();
    } else {
      break;
    }
  }
  return name;
}

void onChange(void* user, uint64_t time, fstHandle handle, const unsigned char* value) {
  auto& state = *static_cast<State*>(user);
  if (!state.anyTime) state.firstTime = time, state.anyTime = true;
  state.lastTime = time;
  if (handle >= state.byHandle.size()) return;
  Signal& s = state.byHandle[handle];
  const auto* v = reinterpret_cast<const char*>(value);
  if (handle == state.clock) {
    if (state.clockLast != '1' && v[0] == '1') ++state.risingEdges;
    state.clockLast = v[0];
  }
  if (s.width <= 0) return;
  if (!s.seen) {
    s.last.assign(v, v + s.width);
    s.seen = true;
    return;
  }
  for (int b = 0; b < s.width; ++b) {
    if (s.last[b] != v[b]) {
      ++s.toggles;
      s.last[b] = v[b];
    }
  }
}

// One waveform's toggles by entry, and its clock's rising edges; false (with a
// message) if it cannot be read.
bool readWave(const std::string& path, const std::string& clockName, std::map<std::string, Entry>& entries,
              uint64_t& cycles) {
  void* ctx = fstReaderOpen(path.c_str());
  if (!ctx) {
    std::fprintf(stderr, "lancer_fst_activity: %s: not an FST waveform (or unreadable)\n", path.c_str());
    return false;
  }
  State state;
  state.byHandle.resize(fstReaderGetMaxHandle(ctx) + 1);
  std::vector<std::string> scope;
  bool clockFound = false;
  while (fstHier* h = fstReaderIterateHier(ctx)) {
    switch (h->htyp) {
      case FST_HT_SCOPE:
        scope.emplace_back(h->u.scope.name);
        break;
      case FST_HT_UPSCOPE:
        if (!scope.empty()) scope.pop_back();
        break;
      case FST_HT_VAR: {
        if (h->u.var.is_alias) break;  // the same handle, counted once
        std::string name;
        for (const auto& s : scope) name += s + ".";
        name += h->u.var.name;
        Signal& s = state.byHandle[h->u.var.handle];
        s.name = baseName(name);
        s.width = int(h->u.var.length);
        if (!clockFound && std::string(h->u.var.name) == clockName) {
          state.clock = h->u.var.handle;
          clockFound = true;
        }
        break;
      }
      default:
        break;
    }
  }
  if (!clockFound) {
    std::fprintf(stderr, "lancer_fst_activity: %s: no signal named %s (the clock; --clock NAME)\n", path.c_str(),
                 clockName.c_str());
    fstReaderClose(ctx);
    return false;
  }
  fstReaderSetFacProcessMaskAll(ctx);
  fstReaderIterBlocks(ctx, onChange, &state, nullptr);
  fstReaderClose(ctx);
  if (state.risingEdges == 0) {
    std::fprintf(stderr, "lancer_fst_activity: %s: the clock %s never rises\n", path.c_str(), clockName.c_str());
    return false;
  }
  std::map<std::string, Entry> mine;
  for (const Signal& s : state.byHandle) {
    if (s.width <= 0 || s.name.empty()) continue;
    Entry& e = mine[s.name];
    e.bits += uint64_t(s.width);
    e.toggles += s.toggles;
  }
  for (const auto& [name, e] : mine) {
    Entry& all = entries[name];
    all.bits = std::max(all.bits, e.bits);
    all.toggles += e.toggles;
  }
  cycles += state.risingEdges;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> paths;
  std::string clockName = "clk_i";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--clock") && i + 1 < argc) {
      clockName = argv[++i];
    } else if (argv[i][0] != '-') {
      paths.emplace_back(argv[i]);
    } else {
      paths.clear();
      break;
    }
  }
  if (paths.empty()) {
    std::fprintf(stderr, "usage: lancer_fst_activity WAVE.fst [WAVE.1.fst ...] [--clock NAME]\n");
    return 2;
  }
  std::map<std::string, Entry> entries;
  uint64_t cycles = 0;
  for (const std::string& path : paths) {
    if (!readWave(path, clockName, entries, cycles)) return 1;
  }
  std::printf("{\n  \"waves\": %zu,\n  \"clock\": \"%s\",\n  \"cycles\": %llu,\n  \"signals\": {", paths.size(),
              clockName.c_str(), static_cast<unsigned long long>(cycles));
  const char* sep = "\n";
  for (const auto& [name, e] : entries) {
    const double rate = double(e.toggles) / double(e.bits) / double(cycles);
    std::printf("%s    \"%s\": {\"bits\": %llu, \"toggles\": %llu, \"per_bit_per_cycle\": %.6g}", sep, name.c_str(),
                static_cast<unsigned long long>(e.bits), static_cast<unsigned long long>(e.toggles), rate);
    sep = ",\n";
  }
  std::printf("\n  }\n}\n");
  return 0;
}
