// LD_PRELOADed into the sanitizer runs of the GPU tests and sward-render (tools/sanitize-and-fuzz.sh): makes
// dlclose() a no-op. The Vulkan loader dlclose()s lavapipe and the validation layer in vkDestroyInstance, before
// LeakSanitizer checks at exit; their leaks then show as "<unknown module>" frames that no suppression can name.
// Keeping them loaded lets tests/sanitize/lsan.supp suppress them by library, and only them.
int dlclose(void* handle) {
    (void)handle;
    return 0;
}
