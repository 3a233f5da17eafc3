#pragma once

#include <cstdint>
#include <vector>

#include <pc/core/cloud.h>

namespace pc::segmentation {

/// Parameters of sphere_vote(). Lengths are multiples of the fruit radius R (estimated from the
/// cloud, or the prior `fruit_radius`) or of the point spacing s, so the result does not change
/// when the cloud is scaled or rotated.
struct SphereVoteParams {
    double fruit_radius = 0;    ///< prior R in the cloud's units; 0: estimated from the cloud
    double normal_scale = 1.0;  ///< × R: the neighbourhood a voting normal is fitted to ...
    /// ... and × s: at least this (3 s over-estimated R and found a third of the fruit at 2 s a
    /// radius; below 2 s a neighbourhood holds too few points for a plane)
    double min_normal_scale = 2.0;
    double cell = 0.25;            ///< × R: the vote accumulator's cells
    double peak_radius = 0.4;      ///< × R: votes within this of a peak support it
    double peak_separation = 0.8;  ///< × R: peaks closer than this are one fruit
    double min_support = 0.1;      ///< a peak needs this × the median peak's support
    /// ... and voters from more than one side: the length of their mean direction to it at most
    /// this (1: all parallel, a flat patch such as a piece of leaf)
    double max_alignment = 0.93;
    /// ... and a surface within 2R curved two ways: the smallest eigenvalue of its normals'
    /// second moment at least this (about 0 on a branch, curved one way; fruit 0.008-0.27)
    double min_two_way = 0.02;
    double reach = 1.5;  ///< × a peak's radius: points farther from every peak keep their cluster
    /// ... unless that rest is a sheet (a leaf, the ground): its smallest standard deviation under
    /// this × its middle one and not curved like a bowl (a quadric over its plane explains under
    /// half its thickness; a fruit's cap of half-angle θ has about 0.29 θ, a hemisphere 0.5;
    /// leaves a few lattice steps wide 0.2-0.45, their thickness being steps or noise)
    double sheet = 0.45;
    /// Solids: vote again with the size the assigned points give (their median distance from
    /// their centre, as in a filled ball) when it exceeds R by this factor
    double solid_refit = 1.15;
    /// A given fruit_radius is a prior: R is the radius the normals measure starting from it,
    /// kept within [prior_low, 1] x the given one (1: the given R as it is)
    double prior_low = 0.9;
    /// An estimated R whose centres claim less than this share of the clustered points is
    /// measured again at a smaller scale (it may be a bunch's) ...
    double recheck_below = 0.95;
    /// ... and the smaller R taken when its centres claim at least this much more of the points
    double recheck_gain = 0.02;
    /// An estimated R whose centres claim less than this share is measured again without the
    /// points whose neighbours' normals spread one way only (the smallest eigenvalue of their
    /// second moment under branch_ratio × the middle one: a branch's side, where the normal lines
    /// meet on its axis at its radius; a sphere's 1, a spheroid's of aspect 1.75 at its waist
    /// about 0.1), and that R taken when under half the first and its centres claim more (0: never)
    double branch_below = 0.5;
    double branch_ratio = 0.15;
    /// DBSCAN left fragments when its median cluster has fewer points: the first rough fruit
    /// size is then taken over points, not clusters (pc_fruitcount warns below the same size)
    double fragment_points = 40;
    /// × the normal neighbourhood h: the points that fit normals and vote are one per cube of
    /// this side (a neighbourhood then holds about 50 on a surface, π h² / (c² / 1.5)): spread
    /// evenly over the surfaces, not in proportion to the points (a strided sample kept an SfM
    /// fruit sampled a fifth as densely as its neighbours too thin for normals: 73 of 80 lemons)
    double vote_cell = 0.3;
    std::uint32_t max_samples =
        100000;  ///< points that fit normals and vote (a strided sample) ...
    /// ... unless the rough size of the clusters that are not sheets (leaves, the ground) then
    /// spans fewer spacings of the sample than this: the sample is thinned less, once, by that
    /// shortfall squared (surfaces) or cubed (solids) (a tree of many fruit is not coarsened;
    /// leaves do not make it finer)
    double min_resolution = 5;
    /// Elongated fruit (two centres on one long axis, or a centre and a leftover end): two parts
    /// closer than join_near × R (leftovers 2.5 R) whose points form one convex body (the width
    /// where two fruit would touch at least join_convex × the chord of the widths at their
    /// centres) are one fruit; where R spans join_resolution spacings (0 near: never), and
    /// coarser only where the joins would leave at least coarse_joins × the count's parts fewer
    /// (touching round fruit sampled so coarsely also read as one body now and then, but seldom
    /// as many: docs/robustness-history.md, session 34). Centres join_near to join_far × R apart
    /// (pods and chili split in two lie up to 2.7 R apart) are joined only where the points at the
    /// join (±0.25 R) also ring the line between them: across it, their smaller second moment at
    /// least join_ring × the larger (the pods of scene 3312 read 0.89-0.99; dates side by side
    /// in 3081, whose points meet in a band, from 0.07)
    double join_near = 1.6;
    double join_far = 2.6;
    double join_ring = 0.5;
    double join_convex = 0.9;
    /// ... the profile's slabs (±0.1 R) at least ±join_slab × the voting sample's spacing: where
    /// R spans under 5 spacings ±0.1 R is under one spacing thick, and most slabs of a coarse
    /// long fruit's parts held under 3 points (4321, cucumber-like at 1.8 spacings: 73 of the 98
    /// pairs the profile tried; session 63)
    double join_slab = 0.5;
    double join_resolution = 6;
    double coarse_joins = 0.2;
    /// Long fruit (bananas, aspect near 3: three or four centres along the axis, the middles
    /// beyond reach of either end): centres 2 to join_line_far × R apart (from 1 R where R spans
    /// 4 spacings or more and the votes around both centres spread along the line between them:
    /// a finger's lie on its axis, a round fruit's in a ball) are also one fruit where the votes
    /// fill the line between them: every stretch of about peak_radius × R between the
    /// two centres' vote balls holds, within peak_radius × R of the line, at least join_line ×
    /// the density of votes in the weaker ball (0: never). Traced over 84 matrix scenes, of the
    /// pairs 2-4 R apart that the profile did not join: 1428 of 2499 pairs of one fruit's
    /// centres read 0.3 or more, 19 of 31256 of different fruit; at 0.3 the 28 banana scenes
    /// 0.462 -> 0.511, the 35 eggplant-like 0.725 -> 0.771, the rest of the matrix ±0. Its votes
    /// are cast again from the fit's voters (their normals kept: 2-3 % of the time and +1 % of
    /// the peak memory on the bench canopies, where fitting the normals again cost 10-15 %)
    /// (docs/robustness-history.md, sessions 49 and 51). Up to join_line_far × R: a spheroid of
    /// aspect a gives its two ends' centres about 2 (a - 1) R apart, 5-6 R for cucumber-like
    /// fruit (a 3.5-4), whose middle's points are a leftover that joins one end only (4 R, the
    /// bananas' reach, left most of them in two: session 63)
    double join_line = 0.3;
    double join_line_far = 6;
    std::uint32_t min_cluster_size = 0;  ///< final clusters with fewer points become noise
    /// ... and those with fewer than this × the median final size: the median fruit's where
    /// the centres claimed most points, leftovers also under a quarter of it (pieces cut off a
    /// fruit), leftovers of more than 50 fruit's points (the wood) not weighed in that share;
    /// else the median part's
    double min_relative_size = 0;

    void validate() const;
};

struct SphereVoteResult {
    std::vector<std::uint32_t> labels;  ///< per point: 1..cluster_count by decreasing size, or 0
    std::uint32_t cluster_count = 0;
    std::uint32_t peaks = 0;  ///< fruit centres found
    double spacing = 0;       ///< s: median nearest-neighbour distance of the points that voted
    double fruit_radius =
        0;                   ///< R used (from the prior, or the estimate; 0 when none was possible)
    bool estimated = false;  ///< R was estimated from the cloud
    /// With a given R: the radius the points' normals give on their own (0: none), a check
    double measured_radius = 0;
    /// An estimated R that was replaced by a smaller one whose centres claimed more points (the
    /// first was likely a bunch's); 0 when the first estimate stood
    double larger_radius = 0;
    bool solid = false;  ///< solid fruit (their outer layer voted), else surfaces
    double claimed = 0;  ///< share of the clustered points given to a fruit centre
    /// The median points of a part counted were the leftovers of more than 50 fruit's points
    /// weighed in the centres' share (min_relative_size): the crumbs beside the wood included.
    /// How a colour class is judged (one whose points crumble is doubtful), not what is counted
    double median_part = 0;
};

/// Counts fruit as spheres, on solid and surface clouds alike, without medians over clusters:
///  1. Normals: a plane fitted (PCA) to each sampled point's clustered neighbours (of any
///     cluster: DBSCAN may cut a fruit into slices) within normal_scale × R; its weight is 1 −
///     λ₁/λ₂ (flat surroundings vote, the isotropic inside of a solid fruit does not).
///  2. R, unless given: where the normal lines of nearby points meet (a sphere's normals all
///     pass through its centre, at distance R): the mode of those distances over many pairs,
///     starting from the median cluster size and refitted once at the scale it gives. A given R
///     is a prior: measured the same way starting from it, and used within [prior_low, 1] × it.
///  3. Votes: each point votes for the centres at p ± R·n (the sign of a normal is unknown; the
///     wrong side scatters over a sphere of 2R). Peaks of the vote density (cells of cell × R,
///     local maxima of 3×3×3 sums, refined by mean shift within peak_radius × R), strongest first,
///     at least peak_separation × R apart and with min_support × the median support, are fruit,
///     unless their voters lie on one side (max_alignment: a piece of leaf) or the surface within
///     2R of the peak is curved one way only (min_two_way: a branch, whose normals meet on its
///     axis).
///  4. Every clustered point goes to the peak nearest relative to the peak's radius (the median
///     distance of its voters), when within `reach` of it; points far from every peak keep their
///     DBSCAN cluster as one more part, or are dropped when that part is a flat `sheet`. Pieces
///     of one fruit that DBSCAN separated join their peak.
///  5. Elongated fruit: two parts close together whose points form one convex body (no waist
///     between them, as two touching fruit have) are one fruit (join_near, join_convex; further
///     apart also ringing the line between them: join_far, join_ring), and two centres whose
///     votes fill the line between them (long fruit: join_line, join_line_far), where R spans
///     join_resolution spacings, and coarser where such pairs are many (coarse_joins).
///  6. On a voxel lattice (the nearest-neighbour distances all one step) where R spans under 2.5
///     steps, the leftovers of step 4 are parted into the pieces the lattice connects (face and
///     edge neighbours): there DBSCAN's eps spans a fruit and joined the caps of a bunch's fruit
///     that no peak took. Random samplings keep their clusters.
/// Label 0 stays noise; non-finite points become noise. Deterministic.
[[nodiscard]] SphereVoteResult sphere_vote(const XyzView& points,
                                           std::vector<std::uint32_t> labels,
                                           const SphereVoteParams& params);

}  // namespace pc::segmentation
