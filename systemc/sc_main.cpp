// libsystemc defines main(), which calls sc_main(); a program that links
// libsystemc.so must therefore define sc_main even when it has its own main()
// (which takes precedence over the library's). Every Lancer program brings its
// own main() and drives SystemC from library code (sw/driver/systemc_isect_device),
// so this definition only satisfies the linker. It is linked into every program
// that links lancer_systemc (systemc/CMakeLists.txt, $<TARGET_OBJECTS:lancer_sc_main>),
// not through the archive, where nothing would pull it in.
#include <cstdio>

#include <systemc>

int sc_main(int, char*[]) {
  std::fputs("lancer: SystemC's main() ran instead of the program's own; "
             "this program has no SystemC entry point\n", stderr);
  return 1;
}
