#pragma once
// Text put into markup: the XDMF file (body, field and set names) and the
// verify report's HTML (check names, sources, messages) escape it here.
#include <string>

namespace kinetofem::post {

// Which quotes a piece of markup text may stand inside.
enum class MarkupQuotes {
  Double,  // element content and "..." attributes (HTML report): ' stays as it is
  Any,     // XML attributes quoted either way (XDMF): ' becomes &apos; too
};

// `text` with & < > " (and ' for MarkupQuotes::Any) replaced by their entities.
std::string escape_markup(const std::string& text, MarkupQuotes quotes);

}  // namespace kinetofem::post
