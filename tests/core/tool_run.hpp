// What a test reads back from a command-line tool it ran: the exit status and the text of
// its standard output and standard error.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace gc_test {

struct RunResult {
    int status = -1;
    std::string out;
    std::string err;
};

inline std::string read_text(const std::filesystem::path& p)
{
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}  // namespace gc_test
