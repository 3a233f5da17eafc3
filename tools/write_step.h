#pragma once
// The end of every single-step tool: what the step did (-v), its warnings, the cloud.

#include <pc/cli/tool.h>
#include <pc/pipeline/steps.h>

namespace pc::tools {

inline void write_step(cli::Streams& io, const pipeline::Step& step) {
    io.note(step.note);
    for (const auto& w : step.warnings) {
        io.warn(w);
    }
    io.write(step.blob);
}

}  // namespace pc::tools
