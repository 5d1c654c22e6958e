// LeakSanitizer's suppressions for the sanitizer tree (docs/stability.md,
// "Sanitizers"): some of assimp 5.2's importers (AMF, IRR, LWO, OpenGEX) leak
// what they allocate while reading, inside libassimp, which Lancer frees
// through aiScene as it must. A leak in Lancer's own code still fails its test.
// LSan calls this hook when it is linked in; elsewhere it is never called.

extern "C" const char* __lsan_default_suppressions();
extern "C" const char* __lsan_default_suppressions() { return "leak:libassimp.so\n"; }
