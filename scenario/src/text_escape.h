// Echoing user input (unknown keys, preset names, file names, command-line arguments) in
// messages without letting it drive the terminal: control characters and other non-printable
// text are shown escaped, and long input is cut.
#ifndef POOL_TOOLS_TEXT_ESCAPE_H
#define POOL_TOOLS_TEXT_ESCAPE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/// Output buffer sizes for pool_escape_text: short for JSON keys and values, long for paths.
#define POOL_ESCAPE_SHORT 96
#define POOL_ESCAPE_LONG 320

/// Writes length bytes of text into out (out_size bytes, NUL-terminated) as printable text:
/// C0 controls, DEL and C1 controls as \u00XX (\u001b for ESC, \u0000 for NUL), bytes that are
/// not valid UTF-8 as \xNN, and Unicode format, bidirectional and separator characters (U+200B
/// to U+200F, U+2028 to U+202E, U+2060 to U+206F, U+061C, U+180E, U+FEFF, U+FFF9 to U+FFFB,
/// U+FFFE, U+FFFF, U+E0000 to U+E007F) as \uXXXX or \UXXXXXXXX: the escapes a JSON file would
/// use. Printable UTF-8, backslashes and quotes included, is copied. When the result does not
/// fit, it is cut at a character boundary and ends with "...(N bytes)", N the input's length.
/// Returns out. text may be NULL when length is 0.
char *pool_escape_text(char *out, size_t out_size, const char *text, size_t length);

/// pool_escape_text of a NUL-terminated string.
char *pool_escape_str(char *out, size_t out_size, const char *text);

#ifdef __cplusplus
}
#endif

#endif
