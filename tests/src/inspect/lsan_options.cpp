// Sanitizer builds only: Mesa's software OpenGL driver (dlopen'ed by VTK through GLX under Xvfb)
// leaks a few hundred bytes per context and is dlclose'd before LeakSanitizer runs, so its
// frames cannot be matched by a suppression. Leak checking is therefore off in the rendering
// test executable only; thaw_inspect's non-rendering code is leak-checked by test_inspect.
extern "C" const char* __asan_default_options() {
  return "detect_leaks=0";
}
