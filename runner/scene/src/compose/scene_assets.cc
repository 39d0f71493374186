// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "compose/scene_assets.hpp"

#include <functional>
#include <map>

#include "mjcf_util.hpp"
#include "mjspec_util.hpp"

namespace mjf::runner {
namespace {

using spec::Elements;
using spec::Name;
using spec::Str;

// Every asset reference of the spec, handed to `visit` (defaults included, so that the text
// written from the spec names only assets it has).
void ForEachAssetReference(mjSpec* s, const std::function<void(mjString*)>& visit) {
  auto geom = [&](mjsGeom* g) {
    visit(g->material);
    visit(g->meshname);
    visit(g->hfieldname);
  };
  auto site = [&](mjsSite* t) {
    visit(t->material);
    visit(t->meshname);
  };
  for (mjsElement* e : Elements(s, mjOBJ_GEOM)) geom(mjs_asGeom(e));
  for (mjsElement* e : Elements(s, mjOBJ_SITE)) site(mjs_asSite(e));
  for (mjsElement* e : Elements(s, mjOBJ_LIGHT)) visit(mjs_asLight(e)->texture);
  for (mjsElement* e : Elements(s, mjOBJ_TENDON)) visit(mjs_asTendon(e)->material);
  for (mjsElement* e : Elements(s, mjOBJ_SKIN)) visit(mjs_asSkin(e)->material);
  for (mjsElement* e : Elements(s, mjOBJ_MESH)) visit(mjs_asMesh(e)->material);
  for (mjsElement* e : Elements(s, mjOBJ_DEFAULT)) {
    mjsDefault* d = mjs_findDefault(s, Name(e).c_str());
    if (!d) continue;
    geom(d->geom);
    site(d->site);
    visit(d->light->texture);
    visit(d->tendon->material);
    visit(d->mesh->material);
  }
}

// A material's textures, one per role (MuJoCo's vector of them has mjNTEXROLE entries).
void ForEachTexture(mjsMaterial* m, const std::function<void(int, const std::string&)>& visit) {
  for (int role = 0; role < mjNTEXROLE; ++role) {
    const char* t = mjs_getInStringVec(m->textures, role);
    if (t && *t) visit(role, t);
  }
}

std::set<std::string> UsedAssets(mjSpec* v, mjsBody* body) {
  std::set<std::string> used;
  auto add = [&used](const mjString* s) {
    if (!Str(s).empty()) used.insert(Str(s));
  };
  for (mjsElement* e = mjs_firstChild(body, mjOBJ_GEOM, 1); e; e = mjs_nextChild(body, e, 1)) {
    mjsGeom* g = mjs_asGeom(e);
    for (const mjString* s : {g->material, g->meshname, g->hfieldname}) add(s);
  }
  for (mjsElement* e = mjs_firstChild(body, mjOBJ_SITE, 1); e; e = mjs_nextChild(body, e, 1)) {
    add(mjs_asSite(e)->material);
    add(mjs_asSite(e)->meshname);
  }
  for (mjsElement* e = mjs_firstChild(body, mjOBJ_LIGHT, 1); e; e = mjs_nextChild(body, e, 1)) {
    add(mjs_asLight(e)->texture);
  }
  for (mjsElement* e : Elements(v, mjOBJ_TENDON)) add(mjs_asTendon(e)->material);
  for (mjsElement* e : Elements(v, mjOBJ_SKIN)) add(mjs_asSkin(e)->material);
  for (mjsElement* e : Elements(v, mjOBJ_MATERIAL)) {
    if (!used.count(Name(e))) continue;
    ForEachTexture(mjs_asMaterial(e), [&](int, const std::string& t) { used.insert(t); });
  }
  return used;
}

void MakeAbsolute(mjString* file, const std::string& folder) {
  if (!Str(file).empty()) mjs_setString(file, mjcf::Join(folder, Str(file)).c_str());
}

}  // namespace

void PrepareVehicleAssets(mjSpec* v, mjsBody* body, const std::string& dir) {
  const std::set<std::string> used = UsedAssets(v, body);
  for (mjtObj type : {mjOBJ_MESH, mjOBJ_HFIELD, mjOBJ_MATERIAL, mjOBJ_TEXTURE}) {
    for (mjsElement* e : Elements(v, type)) {
      if (!used.count(Name(e))) mjs_delete(v, e);
    }
  }
  const std::string meshdir = mjcf::Join(dir, Str(v->compiler.meshdir));
  const std::string texturedir = mjcf::Join(dir, Str(v->compiler.texturedir));
  for (mjsElement* e : Elements(v, mjOBJ_MESH)) MakeAbsolute(mjs_asMesh(e)->file, meshdir);
  for (mjsElement* e : Elements(v, mjOBJ_HFIELD)) MakeAbsolute(mjs_asHField(e)->file, meshdir);
  for (mjsElement* e : Elements(v, mjOBJ_SKIN)) MakeAbsolute(mjs_asSkin(e)->file, meshdir);
  for (mjsElement* e : Elements(v, mjOBJ_TEXTURE)) {
    mjsTexture* t = mjs_asTexture(e);
    MakeAbsolute(t->file, texturedir);
    for (int side = 0; side < 6; ++side) {
      const char* f = mjs_getInStringVec(t->cubefiles, side);
      if (f && *f) mjs_setInStringVec(t->cubefiles, side, mjcf::Join(texturedir, f).c_str());
    }
  }
  mjs_setString(v->compiler.meshdir, "");
  mjs_setString(v->compiler.texturedir, "");
}

void ShareVehicleAssets(mjSpec* scene, const std::set<std::string>& vehicle_assets,
                        const std::vector<std::string>& prefixes) {
  // The shared name of a copy's asset name ("" when it is not one).
  auto shared = [&](const std::string& name) -> std::string {
    for (const std::string& p : prefixes) {
      if (name.compare(0, p.size(), p) == 0 && vehicle_assets.count(name.substr(p.size()))) {
        return name.substr(p.size());
      }
    }
    return "";
  };
  const std::set<std::string> scene_assets = spec::AssetNames(scene);
  std::set<std::string> kept;
  for (mjtObj type : spec::kAssetTypes) {
    for (mjsElement* e : Elements(scene, type)) {
      const std::string to = shared(Name(e));
      if (to.empty()) continue;
      if (scene_assets.count(to) || !kept.insert(to).second) {
        mjs_delete(scene, e);
      } else {
        mjs_setName(e, to.c_str());
      }
    }
  }
  ForEachAssetReference(scene, [&](mjString* ref) {
    const std::string to = shared(Str(ref));
    if (!to.empty()) mjs_setString(ref, to.c_str());
  });
  for (mjsElement* e : Elements(scene, mjOBJ_MATERIAL)) {
    mjsMaterial* m = mjs_asMaterial(e);
    ForEachTexture(m, [&](int role, const std::string& t) {
      if (const std::string to = shared(t); !to.empty()) {
        mjs_setInStringVec(m->textures, role, to.c_str());
      }
    });
  }
}

}  // namespace mjf::runner
