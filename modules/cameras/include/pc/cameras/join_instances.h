#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace pc::cameras {

/// One sighting: view `view` sees point `point` inside its 2D instance `instance` (non-zero).
struct Sighting {
    std::uint32_t point = 0;
    std::uint32_t view = 0;
    std::uint32_t instance = 0;
};

/// Parameters of join_instances().
struct JoinParams {
    /// A group of instances joins a larger group it touches in space (see below) when it holds
    /// at most this times the larger one's points and no view sees the two apart.
    double fragment = 0.5;

    void validate() const;
};

struct JoinResult {
    std::vector<std::uint32_t> labels;  ///< per point: 0, or 1.. by decreasing point count
    std::size_t labelled = 0;           ///< points that got a label
    /// ... of those, points whose label is doubtful: only instances of several fruit saw them,
    /// or as many of their sightings lie outside their label's fruit as in it (masks that
    /// disagree across views)
    std::size_t doubtful = 0;
};

/// 3D instances from the 2D instances of several views (pc_lift --instances). The nodes of a
/// graph are the views' 2D instances; two are linked by the points of `keep` that both contain.
/// Links are taken strongest first (shared points over the larger node's points) and join their
/// nodes' groups unless the joined group would hold two instances of one view: a view's distinct
/// instances are distinct fruit, so the few points either side of a contact, which land in the
/// other fruit's instance in some views, cannot chain two fruit together once each is seen apart.
/// Each point of `keep` then takes the group most of its sightings belong to. A part of a fruit
/// seen only by views that see nothing else of it shares no point with the rest: a group joins a
/// larger one it touches (`touching`: pairs of point indices next to each other in space) when it
/// is at most `fragment` of its size and no view holds an instance of each, most touching first.
/// Returns a label per point (`keep` has one flag per point): 0 for points not kept or never
/// sighted, else 1.. numbering the groups by decreasing point count (renumber_by_size: ties by
/// smallest point index).
/// Deterministic. `sightings` is consumed.
[[nodiscard]] JoinResult join_instances(
    std::vector<Sighting> sightings,
    const std::vector<std::uint8_t>& keep,
    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& touching,
    const JoinParams& params = {});

}  // namespace pc::cameras
