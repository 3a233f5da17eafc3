#pragma once
// Parts of a count that are the tree's wood, told by their colour: a part's mean colour is
// exact where a point's is noise, and the wood shows its colour in the one part far too large
// to be a fruit or a bunch.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <pc/io/points.h>

namespace pc::filters {

struct WoodPartsParams {
    /// A part holding more points than this many times the median part is the wood or the
    /// ground, no fruit nor bunch (a bunch holds up to about 12 fruit).
    double giant = 50;
    /// ... and more than this share of the parts' points: the tree's wood, kept by the colour
    /// rule, is a large share of the points (a trunk and branches 0.29-0.81 over the 16 matrix
    /// scenes the step corrected), a merged mass of leaves or fruit a small one (0.09: green
    /// fruit among leaves, where the leaves' mass was coloured like the fruit)
    double share = 0.2;
    /// Its colour is the wood's, told from the fruit's, where the two lie more than this many
    /// times the fruit parts' own colour spread apart (their median distance from the fruit's
    /// colour) ...
    double apart = 4;
    /// ... and by this CIELAB ΔE at the least (a just noticeable difference: exact colours, such
    /// as a mask export's, have no spread)
    double min_apart = 2.3;
    /// Of the parts nearer the wood's colour than the fruit's, taken nearest first, the wood's
    /// pieces end at a gap: a part more than this many times as far from the wood's colour as
    /// the one before it (and min_apart further), after at least 3 pieces. The parts past it are
    /// fruit the fruit's median colour left on the wood's side (scene 3527: yellow-green fruit
    /// blushed red over most of their surface, 21-44 ΔE from reddish bark's colour, its pieces
    /// 0.4-4.6). Bark pieces spread evenly about the wood's colour, up to 11-15 ΔE out in scenes
    /// 2197 and 3304 (150-180 pieces each); in 64 of the 66 matrix scenes whose wood was told
    /// apart no part lay past such a gap (2052: 5.0 then 11.8 ΔE, 2.4 times; at 2 times, 11
    /// scenes kept one to five bark pieces more). 0: every part nearer goes
    double gap = 3;
    /// Where no part is a giant: the parts coloured more than `apart` × the parts' spread (their
    /// median distance from the parts' median colour; and min_apart) from that median colour go
    /// where they hold under this share of the parts' points and their median part is smaller
    /// than the others' (bark pieces, half a fruit's points or fewer in the matrix scenes
    /// traced: docs/robustness-history.md, session 50). Smaller than half the others' instead
    /// (session 65, to keep fruit-sized parts of another shade: 3360 lost 7 such) moved 136 of
    /// the 235 scenes where such parts went, 79 down by over 0.01 F1 and 8 up, 36 -> 50 off:
    /// the strays of a fruit's size are mostly crumbs too. 0: never
    double stray_share = 0.5;
    void validate() const;
};

struct WoodPartsResult {
    std::vector<std::uint32_t> labels;  ///< per point: 1..count by decreasing size, or 0
    std::uint32_t count = 0;
    std::uint32_t giants = 0;   ///< parts of the wood's size whose colour was told apart
    std::uint32_t dropped = 0;  ///< other parts dropped: coloured like a giant
    /// The fruit parts' colour spread (CIELAB ΔE) beside the first giant told apart; 0: none
    double fruit_colour_spread = 0;
};

/// The colour of a point in CIELAB (D65; L in 0..100), from sRGB channels in [0, 1].
[[nodiscard]] std::array<double, 3> cielab(const io::Rgb& c);

/// Drops the wood from a count (labels 1.. per point, 0 noise; `colours` one per point). Each
/// part of more than `giant` × the median part's points and more than `share` of the parts'
/// points is weighed against the other parts by
/// mean colour (CIELAB; points with a non-finite colour left out): the fruit's colour is the
/// median colour (per channel, each part one vote) of the parts nearer it than the giant's
/// (two means, one held at the giant's colour, started from the parts further from it than the
/// median part). Where the giant's colour lies more than `apart` × those parts' spread (and
/// `min_apart`) from the fruit's, the giant is the wood and goes, with the parts nearer its
/// colour than the fruit's (bark pieces) up to a gap in their distances from its colour (`gap`:
/// fruit the median colour left on the wood's side, such as the reddest of blushed fruit beside
/// reddish bark, lie past it). Where no part is a giant, the wood may be all in pieces: the
/// parts far from the parts' median colour go where they are smaller parts and a minority of the
/// points (`stray_share`). Parts are left alone where a giant is not told apart (coloured as the
/// parts are: mask colours, brown fruit beside brown bark, a merged bunch). Throws
/// pc::InvalidArgument when the sizes differ.
[[nodiscard]] WoodPartsResult wood_parts(std::span<const io::Rgb> colours,
                                         std::vector<std::uint32_t> labels,
                                         const WoodPartsParams& params = {});

}  // namespace pc::filters
