#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/io/read.h>

#include "support/corpus.h"

namespace pc::io {
namespace {

TEST(Malformed, CorpusHasAtLeastTwentyFiveCases) {
    EXPECT_GE(test::malformed_corpus().size(), 25u);
}

TEST(Malformed, EveryCaseIsRejectedWithOneLineNamingTheProblem) {
    for (const auto& m : test::malformed_corpus()) {
        try {
            (void)parse_cloud(m.bytes);
            ADD_FAILURE() << m.name << " was accepted";
        } catch (const IoError& e) {
            const std::string what = e.what();
            EXPECT_FALSE(what.empty()) << m.name;
            EXPECT_EQ(what.find('\n'), std::string::npos) << m.name << ": " << what;
        }
    }
}

TEST(Malformed, HugeClaimsFailBeforeAllocating) {
    // 4e9 points claimed over 24 bytes: rejected by arithmetic, not by a failed allocation.
    for (const char* name : {"billions_claimed", "width_too_big", "ply_huge_count"}) {
        for (const auto& m : test::malformed_corpus()) {
            if (m.name == name) {
                try {
                    (void)parse_cloud(m.bytes);
                    ADD_FAILURE() << name;
                } catch (const IoError& e) {
                    EXPECT_EQ(std::string(e.what()).find("memory"), std::string::npos) << e.what();
                }
            }
        }
    }
}

}  // namespace
}  // namespace pc::io
