// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "compose/scene_blocks.hpp"

#include <cctype>

#include "mjformation/scene/scene.hpp"

namespace mjf::runner {
namespace {

using spec::SpecPtr;
using spec::Str;

// A new spec with the scene's global settings, its world holding one empty frame (the block).
SpecPtr BlockSpec(const std::function<void(mjSpec*)>& globals, mjsFrame** frame) {
  SpecPtr s(mj_makeSpec());
  globals(s.get());
  mjs_setDeepCopy(s.get(), 1);
  *frame = mjs_addFrame(mjs_findBody(s.get(), "world"), nullptr);
  return s;
}

void Attach(mjsElement* parent, const mjsElement* child, const std::string& prefix, mjSpec* into,
            const std::string& vehicle_path) {
  if (!mjs_attach(parent, child, prefix.c_str(), "")) {
    throw SceneError(vehicle_path + ": MuJoCo cannot attach the vehicle: " + mjs_getError(into));
  }
}

// The shared asset a copy's reference uav<i>_<asset> names ("" when it names none).
std::string SharedName(const std::string& ref, const std::set<std::string>& assets) {
  const std::string head = VehiclePrefix(0).substr(0, VehiclePrefix(0).find('0'));  // "uav"
  if (ref.compare(0, head.size(), head) != 0) return "";
  size_t k = head.size();
  while (k < ref.size() && std::isdigit(static_cast<unsigned char>(ref[k]))) ++k;
  if (k == head.size() || k >= ref.size() || ref[k] != '_') return "";
  const std::string asset = ref.substr(k + 1);
  return assets.count(asset) ? asset : "";
}

struct Sharer {
  const std::set<std::string>& assets;
  void operator()(mjString* ref) const {
    if (const std::string to = SharedName(Str(ref), assets); !to.empty()) {
      mjs_setString(ref, to.c_str());
    }
  }
  void Geom(mjsGeom* g) const {
    (*this)(g->material);
    (*this)(g->meshname);
    (*this)(g->hfieldname);
  }
  void Site(mjsSite* s) const {
    (*this)(s->material);
    (*this)(s->meshname);
  }
  // The body's own geoms, sites and lights, then its children's: each element visited once
  // (mjs_nextElement would search the tree from its root for every element).
  void Body(mjsBody* b) const {
    for (mjsElement* e = mjs_firstChild(b, mjOBJ_GEOM, 0); e; e = mjs_nextChild(b, e, 0)) {
      Geom(mjs_asGeom(e));
    }
    for (mjsElement* e = mjs_firstChild(b, mjOBJ_SITE, 0); e; e = mjs_nextChild(b, e, 0)) {
      Site(mjs_asSite(e));
    }
    for (mjsElement* e = mjs_firstChild(b, mjOBJ_LIGHT, 0); e; e = mjs_nextChild(b, e, 0)) {
      (*this)(mjs_asLight(e)->texture);
    }
    for (mjsElement* e = mjs_firstChild(b, mjOBJ_BODY, 0); e; e = mjs_nextChild(b, e, 0)) {
      Body(mjs_asBody(e));
    }
  }
};

}  // namespace

std::vector<SpecPtr> AttachInBlocks(mjSpec* scene, mjsBody* vehicle_body, int first, int last,
                                    const std::function<void(mjSpec*)>& globals,
                                    const std::string& vehicle_path) {
  std::vector<SpecPtr> blocks;
  std::vector<mjsFrame*> frames;  // frames[k]: block k, 10^k vehicles
  auto block = [&](size_t k) {
    while (blocks.size() <= k) {
      mjsFrame* frame = nullptr;
      blocks.push_back(BlockSpec(globals, &frame));
      // The block's own default class becomes a class of the spec it is attached to, under
      // the block's prefix: a name per level keeps those classes apart.
      mjs_setName(mjs_getSpecDefault(blocks.back().get())->element,
                  (kBlockMarker + std::to_string(blocks.size() - 1)).c_str());
      if (frames.empty()) {
        Attach(frame->element, vehicle_body->element, "_", blocks.back().get(), vehicle_path);
      } else {
        for (int d = 0; d < 10; ++d) {
          Attach(frame->element, frames.back()->element, std::to_string(d), blocks.back().get(),
                 vehicle_path);
        }
      }
      frames.push_back(frame);
    }
    return frames[k]->element;
  };
  mjsBody* world = mjs_findBody(scene, "world");
  for (long long i = first + 1; i <= last;) {
    // The largest block that starts at i (i a multiple of 10^k) and ends by `last`.
    size_t k = 0;
    long long size = 1;
    while (i % (10 * size) == 0 && i + 10 * size - 1 <= last) {
      size *= 10;
      ++k;
    }
    const std::string prefix = VehiclePrefix(static_cast<int>(i / size));
    Attach(world->element, block(k), prefix.substr(0, prefix.size() - 1), scene, vehicle_path);
    i += size;
  }
  return blocks;
}

void ShareAssetReferences(mjSpec* scene, const std::set<std::string>& vehicle_assets,
                          bool defaults_refer_to_assets) {
  const Sharer share{vehicle_assets};
  share.Body(mjs_findBody(scene, "world"));
  for (mjsElement* e : spec::Elements(scene, mjOBJ_TENDON)) share(mjs_asTendon(e)->material);
  for (mjsElement* e : spec::Elements(scene, mjOBJ_SKIN)) share(mjs_asSkin(e)->material);
  if (!defaults_refer_to_assets) return;
  // Rare (a vehicle whose default classes name a material or mesh), and a pass per class.
  for (mjsElement* e : spec::Elements(scene, mjOBJ_DEFAULT)) {
    mjsDefault* d = mjs_findDefault(scene, spec::Name(e).c_str());
    if (!d) continue;
    share.Geom(d->geom);
    share.Site(d->site);
    share(d->light->texture);
    share(d->tendon->material);
  }
}

}  // namespace mjf::runner
