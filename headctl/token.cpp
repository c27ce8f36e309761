#include "headctl/token.hpp"

#include "headctl/protocol.hpp"
#include "headctl/uri.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace gc::headctl {

void check_token(std::string_view token)
{
    const bool printable = std::all_of(token.begin(), token.end(), [](char c) { return c > 0x20 && c < 0x7f; });
    if (token.empty() || token.size() > kMaxTokenLength || !printable)
        throw std::invalid_argument("a token is 1 to 64 printable characters without blanks");
}

bool same_secret(std::string_view a, std::string_view b)
{
    unsigned diff = a.size() == b.size() ? 0u : 1u;
    for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned>(a[i] ^ (i < b.size() ? b[i] : 0));
    return diff == 0;
}

std::string read_token_file(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::invalid_argument("cannot read the token file " + path + ": " + std::strerror(errno));
    std::string token;
    std::getline(in, token);
    if (!token.empty() && token.back() == '\r') token.pop_back();
    try {
        check_token(token);
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("the token file " + path + " does not hold a token: " + e.what());
    }
    return token;
}

std::string token_from_environment()
{
    const char* value = std::getenv(kTokenEnvironmentVariable);
    if (!value || !*value) return {};
    try {
        check_token(value);
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(std::string(kTokenEnvironmentVariable) + ": " + e.what());
    }
    return value;
}

void hide_argument(char* argument) { std::fill(argument, argument + std::strlen(argument), '*'); }

void hide_token_in_uri_argument(char* uri)
{
    for (const TextSpan& value : token_values(uri)) std::fill_n(uri + value.offset, value.length, '*');
}

void hide_secret_arguments(int argc, char** argv)
{
    for (int i = 1; i < argc; ++i) {
        const std::string_view a = argv[i];
        if ((a == "--token" || a == "--uri") && i + 1 < argc) {
            ++i;
            a == "--uri" ? hide_token_in_uri_argument(argv[i]) : hide_argument(argv[i]);
        } else if (a.starts_with("--token=")) {
            hide_argument(argv[i] + a.find('=') + 1);
        } else if (a.starts_with("--uri=")) {
            hide_token_in_uri_argument(argv[i] + a.find('=') + 1);
        }
    }
}

}  // namespace gc::headctl
