#pragma once
// The subgrid normal compliance of the grasper's closed jaws pressing the gallbladder (issue 37),
// per surface vertex the press is centred nearest. A press moves every step, so the compliance is
// kept per vertex as it is computed (physics/fem/jaw_subgrid_compliance.h's press: the 10-node
// tets' 4 x 2 cells less the linear footprint, the tangential components free), one vertex at a
// time on a worker thread: a vertex asked for while none is pending starts a worker, whose result
// is adopted adopt_steps later at a fixed step (replays stay bit-identical; the step waits only if
// the worker is slower). Until a vertex has its value the press is the linear footprint's (zero
// subgrid compliance).

#include <future>
#include <memory>
#include <unordered_map>

#include "physics/fem/fem_model.h"
#include "physics/fem/jaw_subgrid_compliance.h"
#include "physics/mesh/mesh_topology.h"

namespace vesica::physics {

class JawPressSubgrid {
 public:
  /// `body`'s rest mesh and `boundary` = its ExtractBoundary (shared with the workers).
  JawPressSubgrid(std::shared_ptr<const FemModel> body, std::shared_ptr<const TetBoundary> boundary,
                  double patch_radius_m, int adopt_steps);
  ~JawPressSubgrid();  // waits for a worker still running
  JawPressSubgrid(const JawPressSubgrid&) = delete;
  JawPressSubgrid& operator=(const JawPressSubgrid&) = delete;

  /// The normal subgrid compliance (m/N, >= 0) of `jaw` pressed at surface vertex `vertex` (the
  /// jaw is the one this vertex is first asked with), at step `step`: zero until it is known.
  double At(int vertex, const RectangularFootprint& jaw, long step);
  int known() const { return static_cast<int>(known_.size()); }

 private:
  void AdoptIfDue(long step);

  std::shared_ptr<const FemModel> body_;
  std::shared_ptr<const TetBoundary> boundary_;
  double patch_radius_m_;
  int adopt_steps_;
  std::unordered_map<int, double> known_;  // vertex -> compliance (0 where the worker failed)
  int pending_vertex_ = -1;
  long pending_adopt_step_ = -1;
  std::future<double> pending_;
};

}  // namespace vesica::physics
