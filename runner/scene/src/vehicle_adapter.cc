// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/scene/vehicle_adapter.hpp"

#include <mujoco/mujoco.h>
#include <sys/stat.h>
#include <tinyxml2.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <set>

#include "mjcf_util.hpp"
#include "mjformation/scene/scene.hpp"

namespace mjf::runner {
namespace {

using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;

// Sections a vehicle brings into the composed scene (scene.cc copies these and only these).
const std::set<std::string> kKeptSections = {"compiler", "option",    "size",     "default",
                                             "asset",    "worldbody", "actuator", "sensor",
                                             "contact",  "tendon",    "equality"};
const char* const kActuatorTags[] = {"general", "motor",    "position",    "velocity", "cylinder",
                                     "muscle",  "adhesion", "intvelocity", "damper"};
const char* const kContractSensors[] = {"pos", "vel", "quat", "gyro"};

bool IsFile(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

// "dir/rel" unless rel is absolute (MuJoCo's rule for model-relative folders and files).
std::string Join(const std::string& dir, const std::string& rel) {
  if (rel.empty() || rel[0] == '/' || dir.empty()) return rel;
  return dir.back() == '/' ? dir + rel : dir + "/" + rel;
}

std::string Describe(const XMLElement* e) {
  std::string out = std::string("<") + e->Name();
  if (const char* n = e->Attribute("name")) out += std::string(" name=\"") + n + "\"";
  return out + ">";
}

class Adapter {
 public:
  explicit Adapter(const VehicleMapping& m) : m_(m), dir_(mjcf::ModelDirectory(m.model_path)) {}

  AdaptedVehicle Run() {
    if (doc_.LoadFile(m_.model_path.c_str()) != tinyxml2::XML_SUCCESS) {
      throw SceneError(m_.body_where + ": cannot read the vehicle model " + m_.model_path + ":" +
                       std::to_string(doc_.ErrorLineNum()) + ": " + doc_.ErrorStr());
    }
    root_ = doc_.RootElement();
    if (!root_ || std::strcmp(root_->Name(), "mujoco") != 0) {
      throw SceneError(m_.model_path + ": not MJCF (no <mujoco> root)");
    }
    int includes = 0;
    InlineIncludes(root_, &includes);
    MergeRepeatedSections();
    XMLElement* body = FindBody();
    ScopeDefaults(body);
    ScopeSizes();
    DropWorldExtras(body);
    DropSections();
    RenameBody(body);
    MapRotors(body);
    MakeRoomForContractNames();
    DropDanglingReferences(body);
    ResolveAssets(body);
    AddImuAndSensors(body);

    tinyxml2::XMLPrinter printer;
    doc_.Print(&printer);
    AdaptedVehicle out;
    out.xml = std::string("<!-- ") + m_.model_path +
              " adapted to the mjformation vehicle contract" + " (docs/VEHICLES.md) -->\n" +
              printer.CStr();
    out.notes = notes_;
    return out;
  }

 private:
  std::string At(const XMLElement* e) const {
    return m_.model_path + ":" + std::to_string(e->GetLineNum());
  }
  void Note(const std::string& s) { notes_.push_back(s); }

  // <include file="..."/>: replaced by the children of the included file's <mujoco>, the file
  // found relative to the model's folder (as MuJoCo does).
  void InlineIncludes(XMLElement* parent, int* count) {
    for (XMLElement* e = parent->FirstChildElement(); e;) {
      if (std::strcmp(e->Name(), "include") != 0) {
        InlineIncludes(e, count);
        e = e->NextSiblingElement();
        continue;
      }
      if (++*count > 100) throw SceneError(At(e) + ": more than 100 <include>s (a cycle?)");
      const char* file = e->Attribute("file");
      if (!file) throw SceneError(At(e) + ": <include> without file");
      const std::string path = Join(dir_, file);
      XMLDocument inc;
      if (inc.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS || !inc.RootElement()) {
        throw SceneError(At(e) + ": <include file=\"" + file + "\">: cannot read " + path);
      }
      tinyxml2::XMLNode* after = e;
      XMLElement* first = nullptr;
      for (const XMLElement* c = inc.RootElement()->FirstChildElement(); c;
           c = c->NextSiblingElement()) {
        after = parent->InsertAfterChild(after, c->DeepClone(&doc_));
        if (!first) first = after->ToElement();
      }
      XMLElement* next = first ? first : e->NextSiblingElement();
      parent->DeleteChild(e);
      e = next;  // the included elements are scanned too (nested includes)
    }
  }

  // MuJoCo allows a section several times (includes produce that); scene.cc reads the first.
  void MergeRepeatedSections() {
    std::map<std::string, XMLElement*> first;
    for (XMLElement* s = root_->FirstChildElement(); s;) {
      XMLElement* next = s->NextSiblingElement();
      auto [it, inserted] = first.emplace(s->Name(), s);
      if (!inserted && std::strcmp(s->Name(), "compiler") != 0 &&
          std::strcmp(s->Name(), "option") != 0 && std::strcmp(s->Name(), "size") != 0) {
        while (XMLElement* c = s->FirstChildElement()) it->second->InsertEndChild(c);
        root_->DeleteChild(s);
      } else if (!inserted) {
        for (auto* a = s->FirstAttribute(); a; a = a->Next())
          it->second->SetAttribute(a->Name(), a->Value());
        root_->DeleteChild(s);
      }
      s = next;
    }
  }

  XMLElement* FindBody() {
    XMLElement* world = root_->FirstChildElement("worldbody");
    std::string top;
    for (XMLElement* b = world ? world->FirstChildElement("body") : nullptr; b;
         b = b->NextSiblingElement("body")) {
      const char* n = b->Attribute("name");
      if (n && m_.body == n) {
        bool free = false;
        for (XMLElement* c = b->FirstChildElement(); c; c = c->NextSiblingElement()) {
          free |= std::strcmp(c->Name(), "freejoint") == 0 ||
                  (std::strcmp(c->Name(), "joint") == 0 && c->Attribute("type", "free"));
        }
        if (!free) {
          throw SceneError(m_.body_where + ": " + At(b) + ": body '" + m_.body +
                           "' has no free joint (<freejoint/> or <joint type=\"free\"/>): a "
                           "vehicle must move freely in the world");
        }
        return b;
      }
      top += (top.empty() ? "'" : ", '") + std::string(n ? n : "(unnamed)") + "'";
    }
    throw SceneError(
        m_.body_where + ": " + m_.model_path + " has no top-level body named '" + m_.body +
        "' in <worldbody> (its top-level bodies: " + (top.empty() ? "none" : top) + ")");
  }

  // The model's top-level defaults would apply to the whole shared scene (the floor too, through
  // scene.cc's merge): they move into a class of their own, which the vehicle's elements use.
  void ScopeDefaults(XMLElement* body) {
    XMLElement* def = root_->FirstChildElement("default");
    if (!def) return;
    bool has_main = false;
    for (XMLElement* c = def->FirstChildElement(); c; c = c->NextSiblingElement()) {
      has_main |= std::strcmp(c->Name(), "default") != 0;
    }
    if (!has_main) return;
    const char* kClass = "mjf_vehicle_defaults";
    XMLElement* scoped = doc_.NewElement("default");
    scoped->SetAttribute("class", kClass);
    while (XMLElement* c = def->FirstChildElement()) scoped->InsertEndChild(c);
    def->InsertEndChild(scoped);
    // Elements that used the top-level defaults now name the class: the body's subtree through
    // childclass (a childclass it has already is nested in the class and inherits from it), the
    // sections outside the body and the assets that take defaults.
    if (!body->Attribute("childclass")) body->SetAttribute("childclass", kClass);
    for (const char* tag : {"actuator", "tendon", "equality", "contact"}) {
      XMLElement* section = root_->FirstChildElement(tag);
      for (XMLElement* e = section ? section->FirstChildElement() : nullptr; e;
           e = e->NextSiblingElement()) {
        if (!e->Attribute("class") && std::strcmp(e->Name(), "exclude") != 0) {
          e->SetAttribute("class", kClass);
        }
      }
    }
    if (XMLElement* asset = root_->FirstChildElement("asset")) {
      for (XMLElement* e = asset->FirstChildElement(); e; e = e->NextSiblingElement()) {
        const bool takes_class =
            std::strcmp(e->Name(), "mesh") == 0 || std::strcmp(e->Name(), "material") == 0;
        if (takes_class && !e->Attribute("class")) e->SetAttribute("class", kClass);
      }
    }
    Note(std::string("scoped the model's top-level <default> settings to the vehicle (class ") +
         kClass + "), so they do not reach the shared scene");
  }

  // Memory sizes written for one vehicle would be too small for a swarm of them: MuJoCo sizes
  // the composed scene itself.
  void ScopeSizes() {
    XMLElement* size = root_->FirstChildElement("size");
    if (!size) return;
    for (const char* a : {"njmax", "nconmax", "nstack", "memory"}) {
      if (size->Attribute(a)) {
        Note(std::string("dropped <size ") + a + "=\"" + size->Attribute(a) +
             "\">: sized for one vehicle, not the swarm");
        size->DeleteAttribute(a);
      }
    }
  }

  // Everything in <worldbody> but the vehicle: floors, lights, cameras, other bodies; and the
  // vehicle's own lights (N copies of a light would relight the shared scene).
  void DropWorldExtras(XMLElement* body) {
    XMLElement* world = body->Parent()->ToElement();
    for (XMLElement* e = world->FirstChildElement(); e;) {
      XMLElement* next = e->NextSiblingElement();
      if (e != body) {
        Note("dropped " + Describe(e) + " (line " + std::to_string(e->GetLineNum()) +
             "): world-level, not part of the vehicle");
        world->DeleteChild(e);
      }
      e = next;
    }
    DropLights(body);
  }
  void DropLights(XMLElement* parent) {
    for (XMLElement* e = parent->FirstChildElement(); e;) {
      XMLElement* next = e->NextSiblingElement();
      if (std::strcmp(e->Name(), "light") == 0) {
        Note("dropped " + Describe(e) + " (line " + std::to_string(e->GetLineNum()) +
             "): lights are the scene's");
        parent->DeleteChild(e);
      } else {
        DropLights(e);
      }
      e = next;
    }
  }

  void DropSections() {
    for (XMLElement* s = root_->FirstChildElement(); s;) {
      XMLElement* next = s->NextSiblingElement();
      if (!kKeptSections.count(s->Name())) {
        Note(std::string("dropped <") + s->Name() + "> (line " + std::to_string(s->GetLineNum()) +
             "): a vehicle brings no " + s->Name() + " into the shared scene");
        root_->DeleteChild(s);
      }
      s = next;
    }
  }

  // Renames element `from` to `to` and every reference to it. `tags`: the element kinds that
  // carry this kind of name; `objtypes`: the objtype/reftype values meaning this kind.
  void Rename(XMLElement* e, const std::set<std::string>& tags, const std::set<std::string>& attrs,
              const std::set<std::string>& objtypes, const std::string& from,
              const std::string& to) {
    if (tags.count(e->Name()) && e->Attribute("name", from.c_str())) {
      e->SetAttribute("name", to.c_str());
    }
    for (const auto& a : attrs) {
      if (e->Attribute(a.c_str(), from.c_str())) e->SetAttribute(a.c_str(), to.c_str());
    }
    if (e->Attribute("objname", from.c_str()) && objtypes.count(Str(e->Attribute("objtype")))) {
      e->SetAttribute("objname", to.c_str());
    }
    if (e->Attribute("refname", from.c_str()) && objtypes.count(Str(e->Attribute("reftype")))) {
      e->SetAttribute("refname", to.c_str());
    }
    for (XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
      Rename(c, tags, attrs, objtypes, from, to);
    }
  }
  static std::string Str(const char* s) { return s ? s : ""; }
  void RenameBodyRefs(const std::string& from, const std::string& to) {
    Rename(root_, {"body"}, {"body", "body1", "body2", "target"}, {"body", "xbody"}, from, to);
  }
  void RenameSiteRefs(const std::string& from, const std::string& to) {
    Rename(root_, {"site"}, {"site", "site1", "site2", "refsite", "cranksite", "slidersite"},
           {"site"}, from, to);
  }
  void RenameActuatorRefs(const std::string& from, const std::string& to) {
    Rename(root_, {std::begin(kActuatorTags), std::end(kActuatorTags)}, {"actuator"}, {"actuator"},
           from, to);
  }

  static bool HasNamed(const XMLElement* e, const char* tag, const std::string& name) {
    if (std::strcmp(e->Name(), tag) == 0 && e->Attribute("name", name.c_str())) return true;
    for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
      if (HasNamed(c, tag, name)) return true;
    }
    return false;
  }

  void RenameBody(XMLElement* body) {
    if (m_.body == "vehicle") return;
    if (HasNamed(body, "body", "vehicle")) {
      throw SceneError(m_.body_where + ": " + m_.model_path + ": body '" + m_.body +
                       "' contains a body named 'vehicle', the name the contract gives the "
                       "vehicle itself: rename it");
    }
    RenameBodyRefs(m_.body, "vehicle");
    Note("renamed body '" + m_.body + "' to 'vehicle'");
  }

  std::vector<XMLElement*> Actuators() const {
    std::vector<XMLElement*> out;
    if (XMLElement* s = root_->FirstChildElement("actuator")) {
      for (XMLElement* a = s->FirstChildElement(); a; a = a->NextSiblingElement()) out.push_back(a);
    }
    return out;
  }

  void MapRotors(XMLElement* body) {
    const auto& want = m_.actuator_names;
    if (m_.rotors.size() != want.size()) {
      std::string names;
      for (const auto& n : want) names += (names.empty() ? "" : ", ") + n;
      throw SceneError(m_.rotors_where + ": lists " + std::to_string(m_.rotors.size()) +
                       " rotors of " + m_.model_path + "; the attitude plugin drives " +
                       std::to_string(want.size()) + " (" + names + "), in that order");
    }
    std::vector<XMLElement*> actuators = Actuators();
    std::string have;
    for (XMLElement* a : actuators) {
      have += (have.empty() ? "" : ", ") + Str(a->Attribute("name"));
    }
    std::vector<XMLElement*> rotor(m_.rotors.size(), nullptr);
    for (size_t k = 0; k < m_.rotors.size(); ++k) {
      for (size_t j = 0; j < k; ++j) {
        if (m_.rotors[j] == m_.rotors[k]) {
          throw SceneError(m_.rotors_where + ": rotor '" + m_.rotors[k] +
                           "' is listed twice; each rotor of " + m_.model_path + " once");
        }
      }
      for (XMLElement* a : actuators) {
        if (a->Attribute("name", m_.rotors[k].c_str())) rotor[k] = a;
      }
      if (!rotor[k]) {
        throw SceneError(m_.rotors_where + ": " + m_.model_path + " has no actuator named '" +
                         m_.rotors[k] + "' (its actuators: " + (have.empty() ? "none" : have) +
                         ")");
      }
      if (const char* site = rotor[k]->Attribute("site"); site && !HasNamed(body, "site", site)) {
        throw SceneError(m_.rotors_where + ": " + At(rotor[k]) + ": rotor '" + m_.rotors[k] +
                         "' acts on site '" + site + "', which is not on body '" + m_.body + "'");
      }
    }
    // A non-rotor actuator that already has a contract name steps aside.
    for (XMLElement* a : actuators) {
      if (std::find(rotor.begin(), rotor.end(), a) != rotor.end()) continue;
      const std::string n = Str(a->Attribute("name"));
      if (std::find(want.begin(), want.end(), n) != want.end()) {
        RenameActuatorRefs(n, "model_" + n);
        Note("renamed actuator '" + n + "' (not a rotor) to 'model_" + n + "'");
      }
    }
    // Two passes, so that a permutation of names (rotors = ["rotor1", "rotor0", ...]) works.
    for (size_t k = 0; k < rotor.size(); ++k) {
      RenameActuatorRefs(m_.rotors[k], "mjf_rotor_tmp_" + std::to_string(k));
    }
    for (size_t k = 0; k < rotor.size(); ++k) {
      RenameActuatorRefs("mjf_rotor_tmp_" + std::to_string(k), want[k]);
      if (m_.rotors[k] != want[k])
        Note("renamed actuator '" + m_.rotors[k] + "' to '" + want[k] + "'");
    }
  }

  // The contract's site `imu` and sensors pos/vel/quat/gyro are added here; the model's own
  // elements of those names keep working under a model_ prefix.
  void MakeRoomForContractNames() {
    if (HasNamed(root_, "site", "imu")) {
      RenameSiteRefs("imu", "model_imu");
      Note(
          "renamed the model's site 'imu' to 'model_imu' (the contract's 'imu' sits at the "
          "centre of mass)");
    }
    if (XMLElement* s = root_->FirstChildElement("sensor")) {
      for (XMLElement* e = s->FirstChildElement(); e; e = e->NextSiblingElement()) {
        for (const char* n : kContractSensors) {
          if (e->Attribute("name", n)) {
            e->SetAttribute("name", (std::string("model_") + n).c_str());
            Note(std::string("renamed the model's sensor '") + n + "' to 'model_" + n + "'");
          }
        }
      }
    }
  }

  static void CollectNames(const XMLElement* e, std::set<std::string>* names) {
    if (const char* n = e->Attribute("name")) names->insert(n);
    for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
      CollectNames(c, names);
    }
  }
  static bool RefersOutside(const XMLElement* e, const std::set<std::string>& names) {
    for (const char* a : mjcf::kReferenceAttributes) {
      const char* v = e->Attribute(a);
      if (v && !names.count(v)) return true;
    }
    for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
      if (RefersOutside(c, names)) return true;
    }
    return false;
  }

  // Sensors, contact pairs, equalities, tendons and other actuators that name something the
  // adapter dropped (a floor geom, a world site) would not compile: they go too.
  void DropDanglingReferences(XMLElement* body) {
    std::set<std::string> names;
    CollectNames(body, &names);
    for (const char* tag : {"tendon", "actuator"}) {
      if (XMLElement* s = root_->FirstChildElement(tag)) CollectNames(s, &names);
    }
    for (const char* tag : {"tendon", "actuator", "sensor", "contact", "equality"}) {
      XMLElement* s = root_->FirstChildElement(tag);
      for (XMLElement* e = s ? s->FirstChildElement() : nullptr; e;) {
        XMLElement* next = e->NextSiblingElement();
        if (RefersOutside(e, names)) {
          Note("dropped <" + std::string(tag) + "> " + Describe(e) + " (line " +
               std::to_string(e->GetLineNum()) + "): refers to an element outside the vehicle");
          s->DeleteChild(e);
        }
        e = next;
      }
    }
  }

  static void CollectAttribute(const XMLElement* e, const char* attr, std::set<std::string>* out) {
    if (const char* v = e->Attribute(attr)) out->insert(v);
    for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
      CollectAttribute(c, attr, out);
    }
  }

  // What the vehicle uses: materials, meshes and height fields named by its geoms, sites and
  // defaults; textures named by the materials kept.
  std::set<std::string> UsedAssets(const XMLElement* body, XMLElement* asset) const {
    std::set<std::string> used;
    for (const char* attr : {"material", "mesh", "hfield"}) {
      CollectAttribute(body, attr, &used);
      if (XMLElement* d = root_->FirstChildElement("default")) CollectAttribute(d, attr, &used);
    }
    for (XMLElement* a = asset->FirstChildElement("material"); a;
         a = a->NextSiblingElement("material")) {
      if (used.count(Str(a->Attribute("name")))) CollectAttribute(a, "texture", &used);
    }
    return used;
  }

  // Each file attribute of the kept asset `a` rewritten to the absolute path of a file that
  // exists under the model's folder + `folder`.
  void PointAtFiles(XMLElement* a, const std::string& folder) const {
    const std::string tag = a->Name();
    for (const char* attr :
         {"file", "fileright", "fileleft", "fileup", "filedown", "filefront", "fileback"}) {
      const char* file = a->Attribute(attr);
      if (!file) continue;
      const std::string path = Join(Join(dir_, folder), file);
      if (!IsFile(path)) {
        throw SceneError(
            At(a) + ": " + Describe(a) + " " + attr + "=\"" + file +
            "\": file not found (looked at " + path + "; " + tag +
            " files are found relative to the model file" +
            (folder.empty()
                 ? ""
                 : " and its " + std::string(tag == "texture" ? "texturedir" : "meshdir")) +
            ")");
      }
      a->SetAttribute(attr, path.c_str());
    }
  }

  // Asset files as MuJoCo finds them: the model's folder + meshdir (meshes, height fields,
  // skins) or texturedir (textures), each defaulting to assetdir; absolute paths as given.
  void ResolveAssets(XMLElement* body) {
    std::string meshdir, texturedir;
    if (XMLElement* c = root_->FirstChildElement("compiler")) {
      const std::string assetdir = Str(c->Attribute("assetdir"));
      meshdir = c->Attribute("meshdir") ? Str(c->Attribute("meshdir")) : assetdir;
      texturedir = c->Attribute("texturedir") ? Str(c->Attribute("texturedir")) : assetdir;
      for (const char* a : {"assetdir", "meshdir", "texturedir"}) c->DeleteAttribute(a);
    }
    XMLElement* asset = root_->FirstChildElement("asset");
    if (!asset) return;
    const std::set<std::string> used = UsedAssets(body, asset);
    std::string unused;
    for (XMLElement* a = asset->FirstChildElement(); a;) {
      XMLElement* next = a->NextSiblingElement();
      const std::string tag = a->Name();
      // Meshes may be named after their file (MuJoCo's default name: the file's stem).
      std::string name = Str(a->Attribute("name"));
      if (name.empty() && a->Attribute("file")) {
        name = Str(a->Attribute("file"));
        name = name.substr(name.find_last_of('/') + 1);
        name = name.substr(0, name.rfind('.'));
      }
      if (tag == "texture" && a->Attribute("type", "skybox")) {
        Note("dropped " + Describe(a) + " (line " + std::to_string(a->GetLineNum()) +
             "): the sky is the scene's");
        asset->DeleteChild(a);
      } else if (!used.count(name)) {
        unused += (unused.empty() ? "" : ", ") + tag + " '" + name + "'";
        asset->DeleteChild(a);
      } else {
        PointAtFiles(a, tag == "texture" ? texturedir : meshdir);
      }
      a = next;
    }
    if (!unused.empty()) Note("dropped assets the vehicle does not use: " + unused);
  }

  // The site `imu` at the centre of mass of the vehicle (with its child bodies), axes those of
  // the body, where the contract's sensors read position, velocity, orientation and body rates.
  void AddImuAndSensors(XMLElement* body) {
    double com[3];
    {
      tinyxml2::XMLPrinter printer;
      doc_.Print(&printer);
      mjModel* m =
          CompileModel(printer.CStr(), m_.model_path + " (adapted to the vehicle contract)");
      mjData* d = mj_makeData(m);
      mj_forward(m, d);
      const int b = mj_name2id(m, mjOBJ_BODY, "vehicle");
      double rel[3];
      mju_sub3(rel, d->subtree_com + 3 * b, d->xpos + 3 * b);
      mju_mulMatTVec(com, d->xmat + 9 * b, rel, 3, 3);  // world offset -> body axes: R^T rel
      mj_deleteData(d);
      mj_deleteModel(m);
    }
    char pos[128];
    std::snprintf(pos, sizeof(pos), "%.17g %.17g %.17g", com[0], com[1], com[2]);
    XMLElement* site = body->InsertNewChildElement("site");
    site->SetAttribute("name", "imu");
    site->SetAttribute("pos", pos);
    site->SetAttribute("quat", "1 0 0 0");
    site->SetAttribute("size", "0.005");
    site->SetAttribute("group", "5");  // not drawn by default
    Note(std::string("added site 'imu' at the centre of mass (") + pos + " in body axes)");

    XMLElement* sensor = root_->FirstChildElement("sensor");
    if (!sensor) sensor = root_->InsertNewChildElement("sensor");
    const char* const kinds[][2] = {
        {"framepos", "pos"}, {"framelinvel", "vel"}, {"framequat", "quat"}};
    for (const auto& k : kinds) {
      XMLElement* s = sensor->InsertNewChildElement(k[0]);
      s->SetAttribute("name", k[1]);
      s->SetAttribute("objtype", "site");
      s->SetAttribute("objname", "imu");
    }
    XMLElement* gyro = sensor->InsertNewChildElement("gyro");
    gyro->SetAttribute("name", "gyro");
    gyro->SetAttribute("site", "imu");
    Note("added sensors pos, vel, quat, gyro at site 'imu'");
  }

  const VehicleMapping& m_;
  const std::string dir_;
  XMLDocument doc_;
  XMLElement* root_ = nullptr;
  std::vector<std::string> notes_;
};

}  // namespace

AdaptedVehicle AdaptVehicle(const VehicleMapping& mapping) { return Adapter(mapping).Run(); }

}  // namespace mjf::runner
