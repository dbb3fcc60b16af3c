// gnuplot started without a shell, script on stdin, PNG on stdout.
#include "plot/gnuplot_driver.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "transport/output_file.h"

extern char** environ;

namespace birotor {
namespace {

// The eight bytes every PNG file starts with (PNG specification, section 5.2).
constexpr char kPngSignature[8] = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n'};
// gnuplot's messages are cut to this many characters in the error line.
constexpr size_t kMaxErrorChars = 400;

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using UniqueFile = std::unique_ptr<std::FILE, FileCloser>;

// gnuplot's stderr as one line: runs of white space become one space.
std::string OneLine(const std::string& text) {
  std::string line;
  for (char c : text) {
    const bool space = c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '^';
    if (space) {
      if (!line.empty() && line.back() != ' ') line += ' ';
    } else {
      line += c;
    }
  }
  while (!line.empty() && line.back() == ' ') line.pop_back();
  if (line.size() > kMaxErrorChars) line = line.substr(0, kMaxErrorChars) + " ...";
  return line;
}

std::string ReadAll(std::FILE* file) {
  std::string text;
  std::rewind(file);
  char buffer[4096];
  size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof(buffer), file)) > 0) text.append(buffer, n);
  return text;
}

bool StartsWithPngSignature(int fd) {
  char head[sizeof(kPngSignature)] = {};
  return ::pread(fd, head, sizeof(head), 0) == static_cast<ssize_t>(sizeof(head)) &&
         std::memcmp(head, kPngSignature, sizeof(head)) == 0;
}

// Runs gnuplot with stdin, stdout and stderr on the given descriptors and
// waits for it. Returns its exit status, or -1 with *error.
int RunGnuplot(int stdin_fd, int stdout_fd, int stderr_fd, std::string* error) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, stdin_fd, STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, stdout_fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, stderr_fd, STDERR_FILENO);
  char program[] = "gnuplot";
  char default_settings[] = "-d";  // no ~/.gnuplot: the same plot for every user
  char* argv[] = {program, default_settings, nullptr};
  pid_t pid = 0;
  const int spawned = ::posix_spawnp(&pid, program, &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    *error = std::string("cannot run gnuplot: ") + std::strerror(spawned) + " (install the Debian package gnuplot-nox)";
    return -1;
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      *error = std::string("waiting for gnuplot failed: ") + std::strerror(errno);
      return -1;
    }
  }
  if (!WIFEXITED(status)) {
    *error = "gnuplot was killed by signal " + std::to_string(WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    return -1;
  }
  return WEXITSTATUS(status);
}

}  // namespace

std::string GnuplotQuoted(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) {
    if (c == '\'') {
      quoted += "''";
    } else if (static_cast<unsigned char>(c) < 0x20 || c == '\x7f') {
      quoted += ' ';
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

bool RenderGnuplotPng(const std::string& script, const std::string& png_path, std::string* error) {
  UniqueFile script_file(std::tmpfile());
  UniqueFile messages(std::tmpfile());
  if (!script_file || !messages) {
    *error = std::string("cannot create a temporary file for gnuplot: ") + std::strerror(errno);
    return false;
  }
  if (std::fwrite(script.data(), 1, script.size(), script_file.get()) != script.size() ||
      std::fflush(script_file.get()) != 0) {
    *error = std::string("cannot write the gnuplot script to a temporary file: ") + std::strerror(errno);
    return false;
  }
  std::rewind(script_file.get());

  // The PNG goes through transport/output_file.h: a temporary file beside
  // png_path, renamed only when gnuplot succeeded and wrote a PNG.
  OutputFile png;
  if (!png.Open(png_path, error)) return false;
  const int output_fd = fileno(png.stream());
  const int status = RunGnuplot(fileno(script_file.get()), output_fd, fileno(messages.get()), error);
  if (status > 0) {
    const std::string text = OneLine(ReadAll(messages.get()));
    *error = "gnuplot failed (exit status " + std::to_string(status) + ")" + (text.empty() ? "" : ": " + text);
    return false;
  }
  if (status < 0) return false;
  const bool temporary = png.write_path() != png.path();  // a regular file, not a device
  if (temporary && !StartsWithPngSignature(output_fd)) {
    *error = "gnuplot wrote no PNG (is the pngcairo terminal installed? Debian package gnuplot-nox)";
    return false;
  }
  return png.Commit(error);
}

}  // namespace birotor
