// What the interaction tells the user, in the user's words: refusals of paper_model and of the
// drag geometry (written for scripts and logs: face and edge numbers, the seed's terms) turned
// into a sentence about what to do, wrapped into short lines that fit the view.
#pragma once

#include <string>

namespace virtual_origami
{
/// The user's sentence for a refusal or a result. Known refusals get a sentence of their own;
/// any other text is kept, without references to the papers, starting with a capital.
std::string forTheUser(const std::string& message);

/// `text` broken at spaces into lines of at most `width` characters (longer words stay whole).
std::string wrapLines(const std::string& text, size_t width);

}  // namespace virtual_origami
