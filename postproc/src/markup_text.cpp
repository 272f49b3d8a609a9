#include "kinetofem/postproc/markup_text.hpp"

namespace kinetofem::post {

std::string escape_markup(const std::string& text, MarkupQuotes quotes) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += quotes == MarkupQuotes::Any ? "&apos;" : "'"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace kinetofem::post
