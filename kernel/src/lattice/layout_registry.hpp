#pragma once
// Internal to the lattice family: the layout kinds the file format knows, each with its reader and writer.
// A layout is added by its own file (the layout and its codec) and one line in layout_registry.cpp.
#include <string>
#include <vector>

#include "lattice/json_fields.hpp"
#include "steady/lattice/layout.hpp"

namespace steady::detail {

struct LayoutCodec {
  const char* kind = "";
  // The layout's own fields (the file's "layout" object without "kind"), and the layout from them; `path` is
  // where the fields sit in the file, for the refusals.
  json (*write)(const Layout& layout) = nullptr;
  LayoutPtr (*read)(const json& fields, const Counts& counts, const std::string& path) = nullptr;
};

const std::vector<LayoutCodec>& layout_codecs();
// InvalidInput naming `path` when no layout has that kind.
const LayoutCodec& layout_codec(const std::string& kind, const std::string& path);

// Each layout's codec, defined beside the layout.
LayoutCodec steady_brick_layout_codec();
LayoutCodec any_order_layout_codec();
LayoutCodec table_layout_codec();

}  // namespace steady::detail
