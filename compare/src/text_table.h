// Text output of the comparison: tables as markdown or aligned columns, numbers formatted for
// them, and files written atomically.
#ifndef POOL_COMPARE_TEXT_TABLE_H
#define POOL_COMPARE_TEXT_TABLE_H

#include <string>
#include <vector>

namespace pool_compare {

/// A number in a printf format, "-" when not finite.
std::string fmt(double x, const char *format = "%.3g");

/// A table as markdown or as text in columns two spaces apart. align_markdown and align_text
/// hold one 'l' (left) or 'r' (right) per column of head. A row shorter than head (a failed run:
/// its message in place of the numbers) reads left and widens only the first three columns.
std::string render_table(const std::vector<std::string> &head, const std::vector<std::vector<std::string>> &rows,
                         bool markdown, const std::string &align_markdown, const std::string &align_text);

/// Writes text to path through a file beside it and a rename, so readers never see half a file;
/// false with "cannot write PATH" in *error.
bool write_file(const std::string &path, const std::string &text, std::string *error);

} // namespace pool_compare

#endif
