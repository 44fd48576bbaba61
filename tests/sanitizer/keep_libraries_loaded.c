/* Preloaded in the sanitizer run only: dlclose becomes a no-op so that
 * drivers and layers the Vulkan loader unloads stay mapped, and
 * LeakSanitizer can name the library behind a leak (lsan.supp matches
 * those names).  Without it their frames print as "<unknown module>". */
int dlclose(void* handle) {
    (void)handle;
    return 0;
}
