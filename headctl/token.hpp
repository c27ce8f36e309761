// Where a head's token comes from besides a URI: a file or the environment, which keep it off
// command lines (every user of the machine can read /proc/PID/cmdline) and out of pipeline
// descriptions.
#pragma once

#include <string>
#include <string_view>

namespace gc::headctl {

inline constexpr const char* kTokenEnvironmentVariable = "GESTURECAM_HEAD_TOKEN";

// Throws std::invalid_argument unless the token is 1 to 64 printable characters without
// blanks (what AUTH can carry).
void check_token(std::string_view token);

// Compares without an early exit, so timing does not reveal how much of a secret matched.
bool same_secret(std::string_view a, std::string_view b);

// The token in the file's first line (a '\r' before its '\n' ignored). Throws
// std::invalid_argument naming the file, never its content, when it cannot be read or
// holds no valid token.
std::string read_token_file(const std::string& path);

// GESTURECAM_HEAD_TOKEN, checked; empty when unset or empty.
std::string token_from_environment();

// Overwrite a command-line argument in place with '*', so that /proc/PID/cmdline stops
// showing the secret once the program has read it: the whole argument, or in a head URI
// the value of its token= parameter. It is visible until then: a file or the environment
// is the safe way.
void hide_argument(char* argument);
void hide_token_in_uri_argument(char* uri);

// Applies the two to a whole command line once it has been parsed: the value of every
// --token (as "--token T" or "--token=T") and the token in every --uri's value.
void hide_secret_arguments(int argc, char** argv);

}  // namespace gc::headctl
