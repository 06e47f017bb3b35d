// Help through the real binary: every verb answers --help and -h with its usage and its section
// of docs/cli.md (read here from the source tree, so a binary embedding a stale or missing
// reference fails), `weft help VERB` prints the same, bare `weft` is a usage error, and the
// usage of `bench` names every benchmark the code registers (bench/weft/bench/BenchNames.h).

#include "CliSupport.h"

#include <weft/bench/BenchNames.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

namespace weft {
namespace {

using test::describe;
using test::runWeft;
using ::testing::HasSubstr;
using ::testing::StartsWith;

const char* const kVerbs[] = {"simulate", "render", "bench", "gradcheck", "optimize", "landscape"};

// docs/cli.md's section for `verb`, read independently of the binary: the lines after the
// heading "## `weft VERB ..." up to the next "## " heading.
std::string referenceSection(const std::string& verb) {
  std::istringstream in(test::readFile(std::string(WEFT_SOURCE_DIR) + "/docs/cli.md"));
  std::string line, body;
  bool inside = false;
  while (std::getline(in, line)) {
    if (inside && line.rfind("## ", 0) == 0) break;
    if (inside) body += line + "\n";
    if (line.rfind("## `weft " + verb + " ", 0) == 0) inside = true;
  }
  return body;
}

// Without leading and trailing blank lines, ending in one newline.
std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of('\n');
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of('\n') - first + 1) + "\n";
}

TEST(HelpCli, EveryVerbAnswersHelpWithItsUsageAndItsReference) {
  for (const char* verb : kVerbs) {
    SCOPED_TRACE(verb);
    const std::string section = referenceSection(verb);
    ASSERT_FALSE(section.empty()) << "docs/cli.md has no section for weft " << verb;
    const test::ProcessResult longForm = runWeft({verb, "--help"});
    EXPECT_EQ(longForm.exitCode, 0) << describe(longForm);
    EXPECT_THAT(longForm.out, StartsWith(std::string("usage: weft ") + verb + " "));
    // Then, after a blank line, the whole section verbatim and nothing else.
    const auto gap = longForm.out.find("\n\n");
    ASSERT_NE(gap, std::string::npos) << longForm.out;
    EXPECT_EQ(longForm.out.substr(gap + 2), trimmed(section));
    EXPECT_TRUE(longForm.err.empty()) << longForm.err;
    const test::ProcessResult shortForm = runWeft({verb, "-h"});
    EXPECT_EQ(shortForm.exitCode, 0) << describe(shortForm);
    EXPECT_EQ(shortForm.out, longForm.out);
    // After other arguments too, even ones that would be errors.
    const test::ProcessResult late = runWeft({verb, "no-such-scene.json", "--help"});
    EXPECT_EQ(late.exitCode, 0) << describe(late);
    EXPECT_EQ(late.out, longForm.out);
    const test::ProcessResult helpVerb = runWeft({"help", verb});
    EXPECT_EQ(helpVerb.exitCode, 0) << describe(helpVerb);
    EXPECT_EQ(helpVerb.out, longForm.out);
  }
}

TEST(HelpCli, TheSectionsDoNotRunIntoEachOther) {
  // simulate's help ends before render's section begins.
  const test::ProcessResult r = runWeft({"simulate", "--help"});
  EXPECT_EQ(r.exitCode, 0) << describe(r);
  EXPECT_THAT(r.out, HasSubstr("positions.npy"));
  EXPECT_EQ(r.out.find("## `weft render"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("Draws PNG frames"), std::string::npos) << r.out;
}

TEST(HelpCli, BareWeftIsAUsageErrorAndHelpListsEveryVerb) {
  const test::ProcessResult bare = runWeft({});
  EXPECT_EQ(bare.exitCode, 2) << describe(bare);
  EXPECT_THAT(bare.err, StartsWith("usage: weft"));
  EXPECT_TRUE(bare.out.empty()) << bare.out;
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"help"}, {"--help"}, {"-h"}}) {
    const test::ProcessResult r = runWeft(args);
    EXPECT_EQ(r.exitCode, 0) << describe(r);
    EXPECT_EQ(r.out, bare.err) << args[0];
  }
  for (const char* verb : kVerbs)
    EXPECT_THAT(bare.err, HasSubstr(std::string("\n  ") + verb + " ")) << verb;
}

TEST(HelpCli, HelpOnAnUnknownVerbIsAnError) {
  const test::ProcessResult r = runWeft({"help", "nosuchverb"});
  EXPECT_EQ(r.exitCode, 2) << describe(r);
  EXPECT_THAT(r.err, StartsWith("error: weft: help nosuchverb: unknown verb\n"));
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST(HelpCli, BenchUsageNamesEveryRegisteredBenchmark) {
  const test::ProcessResult bench = runWeft({"bench", "--help"});
  const test::ProcessResult general = runWeft({"help"});
  ASSERT_EQ(bench.exitCode, 0) << describe(bench);
  // The usage is everything before the reference's first blank line.
  const std::string usage = bench.out.substr(0, bench.out.find("\n\n"));
  const std::string generalBench =
      general.out.substr(general.out.find("\n  bench "),
                         general.out.find("\n  gradcheck ") - general.out.find("\n  bench "));
  for (const char* name : bench::kBenchNames) {
    EXPECT_THAT(usage, HasSubstr(name)) << usage;
    EXPECT_THAT(generalBench, HasSubstr(name)) << generalBench;
    // And the reference's table of benchmarks has a row for it.
    EXPECT_THAT(bench.out, HasSubstr(std::string("| `") + name + "` |")) << name;
  }
  // An unknown name is refused with the same list.
  const test::ProcessResult unknown = runWeft({"bench", "nosuchbench"});
  EXPECT_EQ(unknown.exitCode, 2) << describe(unknown);
  for (const char* name : bench::kBenchNames) EXPECT_THAT(unknown.err, HasSubstr(name));
}

}  // namespace
}  // namespace weft
