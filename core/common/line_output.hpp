// A line-oriented output (a file or standard output) without a user-space buffer: each line
// goes to the kernel in one write call of the whole line, so that a reader following the file
// sees every line as soon as it is written, and a process killed between two lines leaves
// only whole lines behind. Every write and the close are checked.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace gc {

// A failed open, write or close; the message names the output and the system's reason.
class OutputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class LineOutput {
public:
    // Creates or truncates the file at `path`. Throws OutputError.
    static LineOutput create(const std::string& path);
    // The process's standard output (not closed by close()), named "standard output".
    static LineOutput standard_output();

    LineOutput(LineOutput&& other) noexcept;
    LineOutput& operator=(LineOutput&& other) noexcept;
    LineOutput(const LineOutput&) = delete;
    LineOutput& operator=(const LineOutput&) = delete;
    ~LineOutput();

    // Writes `line`, which must end with '\n'. When the write fails part-way, a regular file
    // is cut back to its last whole line before OutputError is thrown.
    void write_line(std::string_view line);
    // Closes the file and reports what the system says about it. Throws OutputError.
    void close();

    const std::string& name() const { return name_; }

private:
    LineOutput(int fd, std::string name, bool owned, bool regular);
    [[noreturn]] void fail(const char* action, int error) const;

    int fd_ = -1;
    std::string name_;
    bool owned_ = false;       // close the descriptor at the end
    bool regular_ = false;     // a regular file: can be cut back after a partial line
    long long committed_ = 0;  // bytes of whole lines written so far
};

}  // namespace gc
