// An image of one size into another, keeping its shape: scaled (bilinear) to the largest size
// that fits, centred, the rest black. A video keeps its first frame's size; frames of another
// size later in a log (a camera size command mid-session) are fitted to it.
#pragma once

#include <cstdint>
#include <vector>

namespace flagsim {

/// `width` x `height` RGB8 pixels => `to_width` x `to_height` RGB8 pixels, rows top to bottom.
std::vector<uint8_t> FitImage(const uint8_t* rgb, int width, int height, int to_width, int to_height);

}  // namespace flagsim
