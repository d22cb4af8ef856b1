#pragma once
// Writes a whole file or nothing: the text goes to NAME.tmp.PID, which is renamed over NAME.
#include <string>

namespace dabench {

// Throws WriteError (naming the file and the system's reason) and leaves NAME as it was.
void write_file_atomically(const std::string& path, const std::string& contents);

}  // namespace dabench
