#pragma once
// Runs the dabench executable (DABENCH_BINARY) as a subprocess for the CLI and end-to-end
// tests: fork + chdir + exec, stdout and stderr redirected into files, exit status captured.
// Every test works in its own fresh temporary folder (TempDir), removed when the test ends:
//   TempDir::work()  the child's working directory (experiments, weights, results live here)
//   TempDir::io()    the captured stdout/stderr files (kept apart, so "no output file was
//                    created" can be checked by listing work())
// Also: small file helpers, a tree snapshot (relative path → contents) and an RFC 4180 CSV
// reader that is independent of harness/core/csv.cpp (so the tests do not check the harness's
// output with the harness's own parser).
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#ifndef DABENCH_BINARY
#error "DABENCH_BINARY (path of the dabench executable) must be defined by the build"
#endif

namespace dabench::test::cli {

namespace fs = std::filesystem;

inline std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

inline void write_text(const fs::path& path, const std::string& text) {
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

// A fresh folder under std::filesystem::temp_directory_path(), removed on destruction.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "dabench-test-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    root_ = pattern;
    fs::create_directories(work());
    fs::create_directories(io());
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(root_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const fs::path& root() const { return root_; }
  fs::path work() const { return root_ / "work"; }
  fs::path io() const { return root_ / "io"; }
  // Writes `text` to work()/relative and returns the path relative to work() (as given).
  std::string write(const std::string& relative, const std::string& text) const {
    write_text(work() / relative, text);
    return relative;
  }
  std::string read(const std::string& relative) const { return read_text(work() / relative); }
  bool exists(const std::string& relative) const { return fs::exists(work() / relative); }

 private:
  fs::path root_;
};

// Every regular file under `folder` (relative path → contents) and every folder (→ "<dir>").
inline std::map<std::string, std::string> snapshot(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    const std::string relative = fs::relative(entry.path(), folder).string();
    files[relative] = entry.is_directory() ? std::string("<dir>") : read_text(entry.path());
  }
  return files;
}

struct CliResult {
  int status = -1;      // exit status; 128 + signal if killed by a signal
  bool signaled = false;
  std::string out;      // stdout
  std::string err;      // stderr
};

// A running dabench process (or another program built on dabench's command line, `program`).
class CliProcess {
 public:
  CliProcess(const std::vector<std::string>& args, const fs::path& cwd, const fs::path& io_folder,
             const std::string& program = DABENCH_BINARY) {
    static int counter = 0;
    const std::string stem = "call" + std::to_string(++counter);
    out_path_ = io_folder / (stem + ".out");
    err_path_ = io_folder / (stem + ".err");
    // Everything the child needs is prepared before fork(): after it, only async-signal-safe calls.
    std::vector<std::string> full{program};
    full.insert(full.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& arg : full) argv.push_back(arg.data());
    argv.push_back(nullptr);
    const std::string cwd_text = cwd.string(), out_text = out_path_.string(), err_text = err_path_.string();
    std::fflush(nullptr);
    pid_ = fork();
    if (pid_ < 0) throw std::runtime_error("fork failed");
    if (pid_ == 0) {
      signal(SIGINT, SIG_DFL);
      signal(SIGTERM, SIG_DFL);
      sigset_t none;
      sigemptyset(&none);
      sigprocmask(SIG_SETMASK, &none, nullptr);
      if (chdir(cwd_text.c_str()) != 0) _exit(126);
      const int in = open("/dev/null", O_RDONLY);
      const int out = open(out_text.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int err = open(err_text.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (in < 0 || out < 0 || err < 0) _exit(126);
      dup2(in, 0);
      dup2(out, 1);
      dup2(err, 2);
      execv(argv[0], argv.data());
      _exit(127);
    }
  }
  ~CliProcess() {
    if (!finished_) {
      kill(pid_, SIGKILL);
      int status = 0;
      waitpid(pid_, &status, 0);
    }
  }
  CliProcess(const CliProcess&) = delete;
  CliProcess& operator=(const CliProcess&) = delete;

  pid_t pid() const { return pid_; }
  void signal_process(int sig) const { kill(pid_, sig); }
  std::string current_stderr() const { return read_text(err_path_); }

  // Waits for the process (killing it after `limit`) and collects its output.
  CliResult wait(std::chrono::seconds limit = std::chrono::seconds(120)) {
    CliResult result;
    int status = 0;
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (true) {
      const pid_t done = waitpid(pid_, &status, WNOHANG);
      if (done == pid_) break;
      if (done < 0) throw std::runtime_error("waitpid failed");
      if (std::chrono::steady_clock::now() > deadline) {
        kill(pid_, SIGKILL);
        waitpid(pid_, &status, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    finished_ = true;
    if (WIFEXITED(status)) {
      result.status = WEXITSTATUS(status);
    } else if (WIFSIGNALED(status)) {
      result.signaled = true;
      result.status = 128 + WTERMSIG(status);
    }
    result.out = read_text(out_path_);
    result.err = read_text(err_path_);
    return result;
  }

 private:
  pid_t pid_ = -1;
  bool finished_ = false;
  fs::path out_path_, err_path_;
};

// Runs `dabench ARGS...` (or `program ARGS...`) in dir.work() and waits for it.
inline CliResult run_dabench(const TempDir& dir, const std::vector<std::string>& args,
                             const std::string& program = DABENCH_BINARY) {
  CliProcess process(args, dir.work(), dir.io(), program);
  return process.wait();
}

// Splits text into lines (without their '\n'); a last line without '\n' is kept.
inline std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const auto end = text.find('\n', start);
    if (end == std::string::npos) {
      lines.push_back(text.substr(start));
      break;
    }
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// RFC 4180: one record per line (fields never contain newlines here), "" escapes a quote.
inline std::vector<std::string> parse_csv_line(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  bool quoted = false, was_quoted = false;
  for (std::size_t k = 0; k < line.size(); ++k) {
    const char c = line[k];
    if (quoted) {
      if (c == '"' && k + 1 < line.size() && line[k + 1] == '"') {
        field += '"';
        ++k;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"' && field.empty() && !was_quoted) {
      quoted = was_quoted = true;
    } else if (c == ',') {
      fields.push_back(field);
      field.clear();
      was_quoted = false;
    } else {
      if (c == '"') throw std::runtime_error("stray quote in CSV line: " + line);
      field += c;
    }
  }
  if (quoted) throw std::runtime_error("unterminated quote in CSV line: " + line);
  fields.push_back(field);
  return fields;
}

// A CSV file with a header line; every record must have as many fields as the header.
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  std::optional<std::size_t> find_column(const std::string& name) const {
    for (std::size_t c = 0; c < header.size(); ++c) {
      if (header[c] == name) return c;
    }
    return std::nullopt;
  }
  std::size_t column(const std::string& name) const {
    const auto c = find_column(name);
    if (!c) throw std::runtime_error("no CSV column " + name);
    return *c;
  }
  const std::string& at(std::size_t row, const std::string& name) const { return rows.at(row).at(column(name)); }
  // A copy without the columns for which drop(name) is true.
  template <class Drop>
  CsvTable without(Drop&& drop) const {
    std::vector<std::size_t> keep;
    CsvTable out;
    for (std::size_t c = 0; c < header.size(); ++c) {
      if (!drop(header[c])) {
        keep.push_back(c);
        out.header.push_back(header[c]);
      }
    }
    for (const auto& row : rows) {
      std::vector<std::string> kept;
      for (const std::size_t c : keep) kept.push_back(row.at(c));
      out.rows.push_back(std::move(kept));
    }
    return out;
  }
};

inline CsvTable parse_csv(const std::string& text) {
  CsvTable table;
  const auto lines = split_lines(text);
  if (lines.empty()) throw std::runtime_error("empty CSV");
  table.header = parse_csv_line(lines[0]);
  for (std::size_t k = 1; k < lines.size(); ++k) {
    table.rows.push_back(parse_csv_line(lines[k]));
    if (table.rows.back().size() != table.header.size()) {
      throw std::runtime_error("CSV line " + std::to_string(k + 1) + " has " + std::to_string(table.rows.back().size()) +
                               " fields, header has " + std::to_string(table.header.size()));
    }
  }
  return table;
}

inline double to_double(const std::string& text) {
  std::size_t used = 0;
  const double value = std::stod(text, &used);
  if (used != text.size()) throw std::runtime_error("not a number: " + text);
  return value;
}

}  // namespace dabench::test::cli
