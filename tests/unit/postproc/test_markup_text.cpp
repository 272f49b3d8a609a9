// escape_markup: the five XML entities, ' only where the markup may quote with it.
#include <gtest/gtest.h>

#include "kinetofem/postproc/markup_text.hpp"

namespace kinetofem::post {
namespace {

TEST(EscapeMarkup, ReplacesTheMarkupCharacters) {
  EXPECT_EQ(escape_markup("a<b> & \"c\"", MarkupQuotes::Double), "a&lt;b&gt; &amp; &quot;c&quot;");
  EXPECT_EQ(escape_markup("plain text", MarkupQuotes::Any), "plain text");
}

TEST(EscapeMarkup, ApostropheOnlyForAnyQuotes) {
  EXPECT_EQ(escape_markup("the arm's bore", MarkupQuotes::Double), "the arm's bore");
  EXPECT_EQ(escape_markup("the arm's bore", MarkupQuotes::Any), "the arm&apos;s bore");
}

}  // namespace
}  // namespace kinetofem::post
