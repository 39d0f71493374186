// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The scene is composed with MuJoCo's model editing API: the world and the vehicle are read
// into specs, the vehicle body attached with its prefix (mjs_attach brings its actuators,
// sensors, contact pairs, tendons and equalities along, in attachment order, so the compiled
// model orders them vehicle by vehicle as the MJCF composition did): the first vehicle alone,
// the others in decimal blocks (scene_blocks.hpp; one attach per vehicle is quadratic in N),
// compiled once and written by MuJoCo's own MJCF writer (scene_text.hpp).
#include "mjformation/scene/scene.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <optional>
#include <unordered_map>

#include "compose/scene_assets.hpp"
#include "compose/scene_blocks.hpp"
#include "compose/scene_text.hpp"
#include "mjcf_util.hpp"
#include "mjspec_util.hpp"

namespace mjf::runner {
namespace {

using spec::SpecPtr;

// Bring your own quadrotor: what the adapter did to the model, for the scene's header comment.
std::string AdapterNotes(const SceneRequest& request) {
  if (request.vehicle_xml.empty()) return "";
  std::string out = ",\n  adapted to the vehicle contract (docs/VEHICLES.md):";
  for (std::string n : request.vehicle_notes) {
    for (size_t k; (k = n.find("--")) != std::string::npos;) n.replace(k, 2, "-");  // XML comment
    out += "\n    " + n;
  }
  return out + "\n";
}

// The vehicle's top-level body: exactly one, named "vehicle".
mjsBody* VehicleBody(mjSpec* vehicle, const std::string& vehicle_path) {
  mjsBody* world = mjs_findBody(vehicle, "world");
  mjsBody* body = nullptr;
  for (mjsElement* e = mjs_firstChild(world, mjOBJ_BODY, 0); e; e = mjs_nextChild(world, e, 0)) {
    if (spec::Name(e) != "vehicle") continue;
    if (body) throw SceneError(vehicle_path + ": two top-level bodies named 'vehicle'");
    body = mjs_asBody(e);
  }
  if (!body) {
    throw SceneError(vehicle_path +
                     ": no top-level <body name=\"vehicle\"> in <worldbody> (see "
                     "docs/ARCHITECTURE.md, vehicle model contract)");
  }
  return body;
}

// A field the vehicle sets (it differs from MuJoCo's default) overrides the scene's: what the
// vehicle's <compiler>, <option> and <size> attributes did when both were merged as MJCF.
void MergeField(const void* from, const void* fallback, void* to, size_t size) {
  if (std::memcmp(from, fallback, size) != 0) std::memcpy(to, from, size);
}
#define MJF_MERGE(from, fallback, to, field) \
  MergeField(&(from).field, &(fallback).field, &(to).field, sizeof((to).field))

void MergeFlags(int from, int fallback, int* to) {
  const int set = from ^ fallback;
  *to = (*to & ~set) | (from & set);
}

void MergeOption(const mjOption& v, const mjOption& d, mjOption& s) {
  for (auto f :
       {&mjOption::timestep, &mjOption::impratio, &mjOption::tolerance, &mjOption::ls_tolerance,
        &mjOption::noslip_tolerance, &mjOption::ccd_tolerance, &mjOption::sleep_tolerance,
        &mjOption::density, &mjOption::viscosity, &mjOption::o_margin}) {
    MergeField(&(v.*f), &(d.*f), &(s.*f), sizeof(mjtNum));
  }
  for (auto f : {&mjOption::integrator, &mjOption::cone, &mjOption::jacobian, &mjOption::solver,
                 &mjOption::iterations, &mjOption::ls_iterations, &mjOption::noslip_iterations,
                 &mjOption::ccd_iterations, &mjOption::sdf_initpoints, &mjOption::sdf_iterations}) {
    MergeField(&(v.*f), &(d.*f), &(s.*f), sizeof(int));
  }
  MJF_MERGE(v, d, s, gravity);
  MJF_MERGE(v, d, s, wind);
  MJF_MERGE(v, d, s, magnetic);
  MJF_MERGE(v, d, s, o_solref);
  MJF_MERGE(v, d, s, o_solimp);
  MJF_MERGE(v, d, s, o_friction);
  MergeFlags(v.disableflags, d.disableflags, &s.disableflags);  // <flag>: one by one
  MergeFlags(v.enableflags, d.enableflags, &s.enableflags);
  MergeFlags(v.disableactuator, d.disableactuator, &s.disableactuator);
}

void MergeCompilerAndSize(const mjSpec& v, const mjSpec& d, mjSpec& s) {
  MJF_MERGE(v, d, s, compiler.autolimits);
  MJF_MERGE(v, d, s, compiler.boundmass);
  MJF_MERGE(v, d, s, compiler.boundinertia);
  MJF_MERGE(v, d, s, compiler.settotalmass);
  MJF_MERGE(v, d, s, compiler.balanceinertia);
  MJF_MERGE(v, d, s, compiler.fitaabb);
  MJF_MERGE(v, d, s, compiler.degree);
  MJF_MERGE(v, d, s, compiler.eulerseq);
  MJF_MERGE(v, d, s, compiler.discardvisual);
  MJF_MERGE(v, d, s, compiler.usethread);
  MJF_MERGE(v, d, s, compiler.fusestatic);
  MJF_MERGE(v, d, s, compiler.inertiafromgeom);
  MJF_MERGE(v, d, s, compiler.inertiagrouprange);
  MJF_MERGE(v, d, s, compiler.alignfree);
  MJF_MERGE(v, d, s, compiler.LRopt);
  for (auto f : {&mjSpec::nemax, &mjSpec::nuserdata, &mjSpec::nuser_body, &mjSpec::nuser_jnt,
                 &mjSpec::nuser_geom, &mjSpec::nuser_site, &mjSpec::nuser_cam,
                 &mjSpec::nuser_tendon, &mjSpec::nuser_actuator, &mjSpec::nuser_sensor,
                 &mjSpec::nkey, &mjSpec::njmax, &mjSpec::nconmax}) {
    MergeField(&(v.*f), &(d.*f), &(s.*f), sizeof(int));
  }
  MJF_MERGE(v, d, s, memory);
  MJF_MERGE(v, d, s, nstack);
}
#undef MJF_MERGE

// An attached body is compiled with its own model's settings: the scene's, as when it was one
// MJCF file; and with equal settings mjs_attach has no conflict to warn about.
void AdoptGlobals(mjSpec* scene, mjSpec* s) {
  const SpecPtr defaults(mj_makeSpec());
  mjString* meshdir = s->compiler.meshdir;
  mjString* texturedir = s->compiler.texturedir;
  s->compiler = scene->compiler;
  s->compiler.meshdir = meshdir;
  s->compiler.texturedir = texturedir;
  s->option = scene->option;
  s->visual = scene->visual;
  s->stat = scene->stat;
  s->authored = scene->authored;
  MergeCompilerAndSize(*scene, *defaults, *s);
}

// MuJoCo sizes the arena (contacts, constraints, stack) by a heuristic quadratic in the degrees
// of freedom, 40 (njmax + nv)^2 bytes (user_model.cc): 146 GB for 10,000 quadrotors, which no
// allocation gets, while a step of 1000 quadrotors with contacts used 41 MB of its 1.8 GB.
// Where the heuristic passes kArenaHeuristicCap (about 3400 quadrotors) the arena grows
// linearly instead; below, MuJoCo's own size is kept, the model as it always was.
constexpr double kArenaHeuristicCap = 16.0 * (1ull << 30);  // bytes
constexpr int64_t kArenaBase = int64_t{64} << 20;           // bytes
constexpr int64_t kArenaPerVehicle = int64_t{256} << 10;    // bytes, six times the 41 kB used
void SizeArena(mjSpec* scene, mjSpec* vehicle, size_t vehicles) {
  if (scene->memory != -1 || scene->nstack != -1) return;  // the model sized it
  int dofs = 0;
  for (mjsElement* e : spec::Elements(vehicle, mjOBJ_JOINT)) {
    const mjtJoint type = mjs_asJoint(e)->type;
    dofs += type == mjJNT_FREE ? 6 : type == mjJNT_BALL ? 3 : 1;
  }
  const double n = (scene->njmax == -1 ? 500 : scene->njmax) + static_cast<double>(dofs) * vehicles;
  if (40.0 * n * n <= kArenaHeuristicCap) return;
  scene->memory = kArenaBase + kArenaPerVehicle * static_cast<int64_t>(vehicles);
}

// The scene's global settings: the vehicle's merged in, then the experiment's time step,
// integrator, contacts and offscreen size. mj_step1/mj_step2 (the split the controllers need to
// read sensors of the current state) supports Euler and the implicit integrators, not RK4; the
// experiments integrate with Euler.
void SetGlobals(mjSpec* scene, mjSpec* vehicle, const SceneRequest& request) {
  const SpecPtr defaults(mj_makeSpec());
  MergeCompilerAndSize(*vehicle, *defaults, *scene);
  MergeOption(vehicle->option, defaults->option, scene->option);
  scene->option.timestep = request.timestep;
  scene->option.integrator = mjINT_EULER;
  if (request.disable_contacts) scene->option.disableflags |= mjDSBL_CONTACT;
  mjVisual& visual = scene->visual;
  visual.global.offwidth = std::max(request.offscreen_width, visual.global.offwidth);
  visual.global.offheight = std::max(request.offscreen_height, visual.global.offheight);
  SizeArena(scene, vehicle, request.positions.size());
  AdoptGlobals(scene, vehicle);
}

// 1 + N prefixed copies of the vehicle body, each at its start position, with the elements that
// refer to it; one copy of the vehicle's assets.
void AttachCopies(mjSpec* scene, mjSpec* vehicle, mjsBody* body, const SceneRequest& request) {
  const std::set<std::string> assets = spec::AssetNames(vehicle);
  mjs_setDeepCopy(scene, 1);  // each copy its own; the vehicle spec stays as it is
  mjsBody* world = mjs_findBody(scene, "world");
  std::vector<std::string> prefixes;
  for (size_t i = 0; i < request.positions.size(); ++i) {
    prefixes.push_back(VehiclePrefix(request.first_vehicle + static_cast<int>(i)));
    mjsFrame* frame = mjs_addFrame(world, nullptr);
    mjsBody* copy =
        mjs_asBody(mjs_attach(frame->element, body->element, prefixes.back().c_str(), ""));
    if (!copy) {
      throw SceneError(request.vehicle_path +
                       ": MuJoCo cannot attach the vehicle: " + mjs_getError(scene));
    }
    std::copy(request.positions[i].begin(), request.positions[i].end(), copy->pos);
    if (i == 0) {
      // The first copy brought the assets; the others refer to them. Deleting a copy's assets
      // from the scene afterwards would cost a pass over the whole scene per asset (quadratic
      // in N), so they are deleted from the small vehicle spec before they can be copied.
      ShareVehicleAssets(scene, assets, prefixes);
      for (mjtObj type : spec::kAssetTypes) spec::DeleteAll(vehicle, type);
    }
  }
  ShareVehicleAssets(scene, assets, prefixes);
}

// The spec's MJCF as MuJoCo writes it (compiled first: MuJoCo writes only a compiled spec).
std::string CompiledXml(mjSpec* s, const std::string& name) {
  mjModel* m = mj_compile(s, nullptr);
  if (!m) throw SceneError(name + ": MuJoCo cannot load the model: " + mjs_getError(s));
  mj_deleteModel(m);
  return spec::SaveXml(s, name);
}

// Each vehicle body (a child of the world named <prefix>vehicle) at its start position.
void PlaceVehicles(mjSpec* s, const SceneRequest& request) {
  std::unordered_map<std::string, size_t> index;
  for (size_t i = 0; i < request.positions.size(); ++i) {
    index[VehiclePrefix(request.first_vehicle + static_cast<int>(i)) + "vehicle"] = i;
  }
  // One pass over the world's children: finding each body by name would search the tree.
  mjsBody* world = mjs_findBody(s, "world");
  for (mjsElement* e = mjs_firstChild(world, mjOBJ_BODY, 0); e; e = mjs_nextChild(world, e, 0)) {
    const auto it = index.find(spec::Name(e));
    if (it == index.end()) continue;
    const auto& p = request.positions[it->second];
    std::copy(p.begin(), p.end(), mjs_asBody(e)->pos);
  }
}

// Whether the vehicle's default classes name assets (materials, meshes, textures).
bool DefaultsReferToAssets(mjSpec* vehicle) {
  bool refers = false;
  auto check = [&](const mjString* s) { refers |= !spec::Str(s).empty(); };
  for (mjsElement* e : spec::Elements(vehicle, mjOBJ_DEFAULT)) {
    const mjsDefault* d = mjs_findDefault(vehicle, spec::Name(e).c_str());
    if (!d) continue;
    for (const mjString* s :
         {d->geom->material, d->geom->meshname, d->geom->hfieldname, d->site->material,
          d->site->meshname, d->light->texture, d->tendon->material}) {
      check(s);
    }
  }
  return refers;
}

// Whether composing in blocks would change the scene's text: with default classes or settings
// of its own, the blocks' classes (MuJoCo's built-in defaults) would differ from the scene's
// main class they sit in; its own frames could look like the blocks' and go with them.
bool BlocksWouldChangeTheText(mjSpec* scene, const std::string& name) {
  const SpecPtr alone(mj_copySpec(scene));
  const std::string xml = CompiledXml(alone.get(), name);
  return xml.find("<default") != std::string::npos || xml.find("<frame") != std::string::npos;
}

// Enough MJCF text for one vehicle in most cases (the quadrotor takes 4 kB): MuJoCo then writes
// the scene once.
constexpr size_t kTextPerVehicle = 8192;

// Composition in O(N log N): the first vehicle attached with the assets, the others in decimal
// blocks (scene_blocks.hpp), their asset references pointed at the shared assets, each placed;
// compiled once; the text without what the blocks left (scene_text.hpp), when the request asks
// for it. Nothing when that text cannot be had; `scene` and `vehicle` are then spent.
std::optional<ComposedScene> ComposeInBlocks(mjSpec* scene, mjSpec* vehicle, mjsBody* body,
                                             const SceneRequest& request, const std::string& name) {
  const std::set<std::string> assets = spec::AssetNames(vehicle);
  const bool defaults_refer = DefaultsReferToAssets(vehicle);
  SceneRequest first = request;
  first.positions.resize(1);
  AttachCopies(scene, vehicle, body, first);
  const int last = request.first_vehicle + static_cast<int>(request.positions.size()) - 1;
  const std::vector<SpecPtr> blocks = AttachInBlocks(
      scene, body, request.first_vehicle, last, [scene](mjSpec* s) { AdoptGlobals(scene, s); },
      request.vehicle_path);
  ShareAssetReferences(scene, assets, defaults_refer);
  PlaceVehicles(scene, request);
  ComposedScene out;
  out.model.reset(mj_compile(scene, nullptr));
  if (!out.model) throw SceneError(name + ": MuJoCo cannot load the model: " + mjs_getError(scene));
  if (!request.write_text) return out;
  std::optional<std::string> xml = WithoutBlocks(
      spec::SaveXml(scene, name, kTextPerVehicle * request.positions.size()), kBlockMarker);
  if (!xml) return std::nullopt;
  out.xml = std::move(*xml);
  return out;
}

// What composition changes of a contract-form model's <option> (an adapted model's notes say it
// from the MJCF, NoteModelOptions): the time step and integrator are the experiment's; the
// physics settings the vehicle sets (they differ from MuJoCo's defaults) hold for the whole
// scene, every vehicle alike.
std::vector<std::string> ContractOptionNotes(const mjOption& v, const mjOption& d,
                                             uint64_t authored, const SceneRequest& request) {
  std::vector<std::string> notes;
  char text[200];
  // A timestep the model writes is replaced even when it equals MuJoCo's default (0.002), so
  // the parser's authored mask (bit 0: timestep, the first field of MJOPTION_FIELDS) says
  // whether the model gave one.
  const bool timestep_given = (authored & 1u) != 0 || v.timestep != d.timestep;
  if (timestep_given && v.timestep != request.timestep) {
    std::snprintf(text, sizeof(text),
                  "the model's <option timestep=\"%g\"> is replaced by the experiment's ([run] "
                  "timestep = %g)",
                  v.timestep, request.timestep);
    notes.push_back(text);
  }
  if (v.integrator != mjINT_EULER) {
    notes.push_back(
        "the model's <option integrator> is replaced by Euler (the runner's mj_step1/mj_step2 "
        "split cannot run RK4)");
  }
  auto vec3 = [&](const char* name, const mjtNum* from, const mjtNum* fallback) {
    if (std::memcmp(from, fallback, 3 * sizeof(mjtNum)) == 0) return;
    std::snprintf(text, sizeof(text),
                  "kept the model's <option %s=\"%g %g %g\"> for the whole scene", name, from[0],
                  from[1], from[2]);
    notes.push_back(text);
  };
  vec3("gravity", v.gravity, d.gravity);
  vec3("wind", v.wind, d.wind);
  auto scalar = [&](const char* name, mjtNum from, mjtNum fallback) {
    if (from == fallback) return;
    std::snprintf(text, sizeof(text),
                  "kept the model's <option %s=\"%g\"> for the whole scene: MuJoCo's fluid "
                  "forces act on every vehicle alike",
                  name, from);
    notes.push_back(text);
  };
  scalar("density", v.density, d.density);
  scalar("viscosity", v.viscosity, d.viscosity);
  if (v.disableflags != d.disableflags || v.enableflags != d.enableflags) {
    notes.push_back("kept the model's <option><flag ...> settings for the whole scene");
  }
  return notes;
}

std::string Header(const SceneRequest& request) {
  return std::string("<!-- Composed by mjformation from ") + request.scene_path + " and " +
         std::to_string(request.positions.size()) + " copies of " + request.vehicle_path +
         AdapterNotes(request) + " -->\n";
}

}  // namespace

std::string VehiclePrefix(int vehicle) { return "uav" + std::to_string(vehicle) + "_"; }

void ModelDeleter::operator()(mjModel_* m) const { mj_deleteModel(m); }

ComposedScene ComposeScene(const SceneRequest& request, const std::string& name) {
  const SpecPtr scene = spec::Parse(request.scene_path, "", request.scene_path, "scene model");
  const bool adapted = !request.vehicle_xml.empty();
  const SpecPtr vehicle =
      spec::Parse(request.vehicle_path, request.vehicle_xml,
                  request.vehicle_path + (adapted ? " (adapted)" : ""), "vehicle model");
  mjsBody* body = VehicleBody(vehicle.get(), request.vehicle_path);
  if (request.strip_actuators) spec::DeleteAll(vehicle.get(), mjOBJ_ACTUATOR);
  spec::DeleteAll(vehicle.get(), mjOBJ_KEY);  // a vehicle's keyframes do not fit the swarm
  PrepareVehicleAssets(vehicle.get(), body, mjcf::ModelDirectory(request.vehicle_path));
  mjs_setString(scene->modelname, "mjformation");
  ComposedScene out;
  if (!adapted) {
    const SpecPtr defaults(mj_makeSpec());
    out.notes =
        ContractOptionNotes(vehicle->option, defaults->option, vehicle->authored.option, request);
  }
  SetGlobals(scene.get(), vehicle.get(), request);
  if (request.positions.size() > 1 && !BlocksWouldChangeTheText(scene.get(), name)) {
    const SpecPtr scene_copy(mj_copySpec(scene.get())), vehicle_copy(mj_copySpec(vehicle.get()));
    if (std::optional<ComposedScene> blocks =
            ComposeInBlocks(scene_copy.get(), vehicle_copy.get(),
                            VehicleBody(vehicle_copy.get(), request.vehicle_path), request, name)) {
      out.model = std::move(blocks->model);
      if (request.write_text) out.xml = Header(request) + blocks->xml;
      return out;
    }
  }
  AttachCopies(scene.get(), vehicle.get(), body, request);
  out.model.reset(mj_compile(scene.get(), nullptr));
  if (!out.model) {
    throw SceneError(name + ": MuJoCo cannot load the model: " + mjs_getError(scene.get()));
  }
  if (request.write_text) out.xml = Header(request) + spec::SaveXml(scene.get(), name);
  return out;
}

mjModel_* CompileModel(const std::string& xml, const std::string& name) {
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  const char* file = "mjformation_scene.xml";
  if (mj_addBufferVFS(&vfs, file, xml.data(), static_cast<int>(xml.size())) != 0) {
    mj_deleteVFS(&vfs);
    throw SceneError(name + ": cannot allocate the in-memory model file");
  }
  char error[1024] = {0};
  mjModel* m = mj_loadXML(file, &vfs, error, sizeof(error));
  mj_deleteVFS(&vfs);
  if (!m) throw SceneError(name + ": MuJoCo cannot load the model: " + error);
  return m;
}

}  // namespace mjf::runner
