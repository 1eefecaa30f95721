/* zscan web — the teaching page and its engine, as the build embeds
 * them (web/embed.cmake): the page's HTML with its two marks, and the
 * emscripten module's JavaScript (the WebAssembly inside it), or "" when
 * zscan was built without emscripten. */
#ifndef ZS_WEB_TEACH_PAGE_H
#define ZS_WEB_TEACH_PAGE_H

extern const char zs_teach_page_html[];
extern const char zs_teach_module_js[];

#endif
