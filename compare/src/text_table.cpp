#include "text_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace pool_compare {

std::string fmt(double x, const char *format) {
	if (!std::isfinite(x))
		return "-";
	char buf[64];
	std::snprintf(buf, sizeof buf, format, x);
	return buf;
}

std::string render_table(const std::vector<std::string> &head, const std::vector<std::vector<std::string>> &rows,
                         bool markdown, const std::string &align_markdown, const std::string &align_text) {
	std::ostringstream out;
	if (markdown) {
		out << "|";
		for (const std::string &h : head)
			out << " " << h << " |";
		out << "\n|";
		for (size_t i = 0; i < head.size(); ++i)
			out << (align_markdown[i] == 'r' ? "---:|" : "---|");
		out << "\n";
		for (const auto &row : rows) {
			out << "|";
			for (size_t i = 0; i < head.size(); ++i)
				out << " " << (i < row.size() ? row[i] : "") << " |";
			out << "\n";
		}
		return out.str();
	}
	std::vector<size_t> width(head.size());
	for (size_t i = 0; i < head.size(); ++i)
		width[i] = head[i].size();
	for (const auto &row : rows)
		for (size_t i = 0; i < row.size() && i < head.size(); ++i)
			if (row.size() == head.size() || i < 3)
				width[i] = std::max(width[i], row[i].size());
	auto line = [&](const std::vector<std::string> &row) {
		for (size_t i = 0; i < row.size(); ++i) {
			const bool left = align_text[i] == 'l' || row.size() != head.size();
			const std::string &cell = row[i];
			const std::string pad(cell.size() < width[i] ? width[i] - cell.size() : 0, ' ');
			out << (i ? "  " : "") << (left ? cell + (i + 1 < row.size() ? pad : "") : pad + cell);
		}
		out << "\n";
	};
	line(head);
	for (const auto &row : rows)
		line(row);
	return out.str();
}

bool write_file(const std::string &path, const std::string &text, std::string *error) {
	const std::string tmp = path + ".tmp";
	FILE *f = std::fopen(tmp.c_str(), "wb");
	bool ok = f && std::fwrite(text.data(), 1, text.size(), f) == text.size();
	if (f)
		ok = std::fclose(f) == 0 && ok;
	if (ok)
		ok = std::rename(tmp.c_str(), path.c_str()) == 0;
	if (!ok) {
		std::remove(tmp.c_str());
		*error = "cannot write " + path;
	}
	return ok;
}

} // namespace pool_compare
