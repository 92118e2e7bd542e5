#pragma once
// Replacing a file so that a reader, or a crash, sees either the old file or
// the complete new one, never a torn mix: write a temporary file in the same
// directory, flush it to disk, rename it over the target, sync the directory.
#include <functional>
#include <string>

namespace gs {

// "<path>.tmp<pid>": in the target's directory (rename is atomic only within
// one file system), unique per process.
std::string temporary_path_for(const std::string& path);

// Calls write(temporary path), fsyncs the temporary file, renames it to
// `path` and fsyncs the directory. On any error the temporary file is removed
// and the error rethrown; `path` is then untouched.
void write_atomically(const std::string& path, const std::function<void(const std::string& temporary)>& write);

}  // namespace gs
