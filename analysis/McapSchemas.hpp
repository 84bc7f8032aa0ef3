// SPDX-License-Identifier: Apache-2.0
#pragma once
// Schemas an MCAP file carries beside its messages, embedded at build time
// (idl/gen_schemas.py) so that an installed flatsat needs no source tree.
#include <string_view>

namespace flatsat::analysis {

/// The OMG IDL text of a topic type ("flatsat::msg::TruthState"), self-contained
/// as MCAP's `omgidl` schema encoding asks (includes inlined, no preprocessor
/// directives); empty when no topic has that type.
std::string_view omgIdlSchema(std::string_view type_name);

/// Foxglove's published JSON schema titled `name` ("foxglove.FrameTransform",
/// "foxglove.Log"; data/foxglove); empty when not embedded.
std::string_view foxgloveJsonSchema(std::string_view name);

}  // namespace flatsat::analysis
