/* Preloaded (LD_PRELOAD) into the sanitizer test runs by
 * scripts/test-sanitizers.sh: dlclose() does nothing, so libraries opened at
 * run time (OpenMPI's mca_*.so plugins, unloaded by MPI_Finalize) stay mapped
 * until exit. LeakSanitizer then names them in its stacks, and their one-time
 * allocations are suppressed by name in lsan.supp; unloaded, they show as
 * "<unknown module>", which no suppression can match. */
int dlclose(void* handle) {
  (void)handle;
  return 0;
}
