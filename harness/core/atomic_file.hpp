#pragma once
// Writes a whole file or nothing: the text goes to NAME.tmp, which is renamed over NAME.
#include <string>

namespace dabench {

void write_file_atomically(const std::string& path, const std::string& contents);  // throws InputError

}  // namespace dabench
