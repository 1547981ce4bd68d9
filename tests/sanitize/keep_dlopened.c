/* Preloaded into the MPI ranks of the sanitizer stage (tests/cli/scenes_mini_test.cpp): dlclose does
 * nothing, so Open MPI's components stay mapped until exit. Open MPI unloads them at MPI_Finalize,
 * and LeakSanitizer, which reports at exit, would then show their allocations as "unknown module"
 * frames that no suppression can name (Debian's Open MPI 4.1 has no mca_base_component_disable_dlclose).
 * With the components mapped, tests/sanitize/lsan.supp names them (mca_*.so). */
int dlclose(void* handle) {
  (void)handle;
  return 0;
}
