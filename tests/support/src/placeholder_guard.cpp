// Keeps kinetofem_test_support a real library while it has no other sources.
namespace kinetofem::testing {
int support_library_anchor() { return 0; }
}  // namespace kinetofem::testing
