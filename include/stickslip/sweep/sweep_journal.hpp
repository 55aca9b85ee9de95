#pragma once
/// \file sweep_journal.hpp
/// \brief A sweep's journal: each finished item's outcome appended to a file and flushed as it
/// arrives, so that a sweep that ends early (a killed job, a failed node) keeps what it finished
/// and a later run resumes it: the items already in the journal are not run again
/// (docs/sweeps.md, "Keeping and resuming").
///
/// The file is text: a first line `stickslip-sweep-journal <settings>` (the caller's description
/// of the sweep: count, parameters, anything the rows depend on), then one line per finished
/// item, `<k> ok <row>` or `<k> error <message>` (backslashes and line breaks escaped as \\, \n).
/// A last line without its line break (the process died while writing it) is not an item.

#include "stickslip/detail/validate.hpp"
#include "stickslip/sweep/sweep.hpp"

#include <cerrno>
#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace stickslip {

namespace detail {
/// `s` with \ as \\ and line breaks as \n (\r as \r): one line of the journal.
inline std::string journal_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    if (c == '\\') out += "\\\\";
    else if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else out += c;
  }
  return out;
}
/// Inverse of journal_escape.
inline std::string journal_unescape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '\\' || i + 1 == s.size()) {
      out += s[i];
      continue;
    }
    const char c = s[++i];
    out += c == 'n' ? '\n' : c == 'r' ? '\r' : c;
  }
  return out;
}
/// The journal's first line for `settings`.
inline std::string journal_head(const std::string& settings) {
  return "stickslip-sweep-journal " + journal_escape(settings);
}
}  // namespace detail

/// The outcomes a journal holds: entry k is set when item k finished (the latest line of k).
/// Throws std::invalid_argument naming `path` when the file is not a journal of these
/// `settings` (another sweep's: resuming it would mix two sweeps) or names an item k >= count;
/// std::runtime_error when it cannot be read. A missing file is an empty journal.
inline std::vector<std::optional<SweepOutcome>> read_sweep_journal(const std::string& path,
                                                                   const std::string& settings,
                                                                   std::size_t count) {
  std::vector<std::optional<SweepOutcome>> done(count);
  if (!std::filesystem::exists(path)) return done;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("read_sweep_journal: cannot read " + path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  std::size_t begin = 0, line_no = 0;
  for (std::size_t end; (end = text.find('\n', begin)) != std::string::npos; begin = end + 1) {
    const std::string line = text.substr(begin, end - begin);
    if (++line_no == 1) {
      if (line != detail::journal_head(settings))
        throw std::invalid_argument("read_sweep_journal: " + path +
                                    " is the journal of another sweep (its first line is '" + line +
                                    "', this sweep's '" + detail::journal_head(settings) + "')");
      continue;
    }
    // "<k> ok <row>" or "<k> error <message>"
    const std::size_t a = line.find(' ');
    const std::size_t b = a == std::string::npos ? a : line.find(' ', a + 1);
    const std::string index = line.substr(0, a), kind = a == std::string::npos ? "" : line.substr(a + 1, b - a - 1);
    char* stop = nullptr;
    errno = 0;
    const unsigned long long k = std::strtoull(index.c_str(), &stop, 10);
    if (b == std::string::npos || index.empty() || *stop != '\0' || errno != 0 || (kind != "ok" && kind != "error"))
      throw std::invalid_argument("read_sweep_journal: " + path + ", line " + std::to_string(line_no) +
                                  ": expected '<k> ok <row>' or '<k> error <message>'");
    if (k >= count)
      throw std::invalid_argument("read_sweep_journal: " + path + ", line " + std::to_string(line_no) +
                                  ": item " + index + " is not one of this sweep's " + std::to_string(count) +
                                  " items");
    SweepOutcome o;
    o.ok = kind == "ok";
    (o.ok ? o.row : o.error) = detail::journal_unescape(line.substr(b + 1));
    done[static_cast<std::size_t>(k)] = std::move(o);
  }
  return done;  // (a head cut short, or none: nothing finished yet)
}

/// Appends outcomes to a journal, each line flushed to the file as it is written.
class SweepJournal {
 public:
  /// Opens `path` for the sweep described by `settings`: `resume` appends to the journal an
  /// earlier run left (read_sweep_journal, called first, checks that it is this sweep's and
  /// tells what it holds), else starts a new one (the file
  /// truncated to its first line). A journal whose last line was cut short is cut back to its
  /// last whole line first. Throws std::runtime_error when the file cannot be written.
  SweepJournal(const std::string& path, const std::string& settings, bool resume) : path_(path) {
    std::string keep;
    if (resume) {
      std::ifstream in(path, std::ios::binary);
      std::stringstream buffer;
      if (in) buffer << in.rdbuf();
      keep = buffer.str();
      keep.resize(keep.rfind('\n') == std::string::npos ? 0 : keep.rfind('\n') + 1);
    }
    if (keep.empty()) keep = detail::journal_head(settings) + '\n';
    out_.open(path, std::ios::binary | std::ios::trunc);
    out_ << keep;
    out_.flush();
    if (!out_) throw std::runtime_error("SweepJournal: cannot write " + path);
  }

  /// Appends item k's outcome and flushes it. Throws std::runtime_error when the write fails.
  void record(std::size_t k, const SweepOutcome& o) {
    out_ << k << (o.ok ? " ok " : " error ") << detail::journal_escape(o.ok ? o.row : o.error) << '\n';
    out_.flush();
    if (!out_) throw std::runtime_error("SweepJournal: cannot write " + path_);
  }

  /// The journal's file.
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ofstream out_;
};

}  // namespace stickslip
