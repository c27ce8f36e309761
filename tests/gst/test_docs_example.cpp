// The C example in docs/metadata.md is the one the tests compile and run
// (tests/gst/read_meta_example.c), so the documentation cannot drift from the API.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace {

std::string read_file(const std::string& path)
{
    std::ifstream in(path);
    EXPECT_TRUE(in) << "cannot read " << path;
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(DocsExample, MetadataDocEmbedsTheTestedExample)
{
    const char* root = std::getenv("GESTURECAM_SOURCE_ROOT");
    ASSERT_NE(root, nullptr);
    const std::string doc = read_file(std::string(root) + "/docs/metadata.md");
    const std::string example = read_file(std::string(root) + "/tests/gst/read_meta_example.c");
    const std::string fence = "```c\n";
    const size_t start = doc.find(fence);
    ASSERT_NE(start, std::string::npos) << "no ```c block in docs/metadata.md";
    const size_t end = doc.find("```\n", start + fence.size());
    ASSERT_NE(end, std::string::npos);
    EXPECT_EQ(doc.substr(start + fence.size(), end - start - fence.size()), example);
}

}  // namespace
