#include <sealfe/film_loads.h>

namespace sealfe
{
nlohmann::json FilmLoads::to_json() const
{
  return {{"force_z", force_z},
          {"moment_x", moment_x},
          {"moment_y", moment_y},
          {"moment_restoring", moment_restoring},
          {"moment_transverse", moment_transverse},
          {"leakage_inner", leakage_inner},
          {"leakage_outer", leakage_outer},
          {"friction_torque", friction_torque},
          {"min_film", min_film},
          {"max_pressure", max_pressure},
          {"min_pressure", min_pressure},
          {"cavitated_fraction", cavitated_fraction},
          {"area", area},
          {"squeeze_flow", squeeze_flow}};
}
} // namespace sealfe
