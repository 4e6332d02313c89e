#include "lattice/layout_registry.hpp"

#include "steady/core/errors.hpp"

namespace steady::detail {

const std::vector<LayoutCodec>& layout_codecs() {
  static const std::vector<LayoutCodec> all{
      steady_brick_layout_codec(),
      any_order_layout_codec(),
      table_layout_codec(),
  };
  return all;
}

const LayoutCodec& layout_codec(const std::string& kind, const std::string& path) {
  std::string known;
  for (const LayoutCodec& c : layout_codecs()) {
    if (kind == c.kind) return c;
    known += (known.empty() ? "" : ", ") + std::string(c.kind);
  }
  fail_input(path, "unknown layout kind '" + kind + "' (this build knows " + known + ")");
}

}  // namespace steady::detail
