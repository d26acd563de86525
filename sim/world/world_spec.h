// A world description: ground, start pose, exploration box and object groups (fixed or
// randomly placed). Plain structs with validation; YAML is converted in tools/ only.
// Sizes drawn from ranges depend on the spec alone; placements depend on the seed, so a
// different seed moves objects without changing their counts or sizes.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/common/config_fields.h"
#include "core/geometry/world_truth.h"

namespace msb {

/// Object kinds the generator knows.
const std::vector<std::string>& worldObjectKinds();

/// A group of objects of one kind.
struct ObjectGroupSpec {
  std::string kind;  ///< building, tower, car, suv, bus, fire_truck, ambulance, tree, rod, pole, wall, rock, gazebo,
                     ///< house, pillar, dumpster
  /// The source's name of a fixed object (e.g. the Gazebo model "House 1_clone" of the authors'
  /// world file); listed by `msbench world show`. Empty: the id alone (kind_n).
  std::string name;
  int count = 1;                   ///< number of objects
  std::optional<Vec2> at;          ///< fixed position (count must be 1)
  std::optional<Vec2> region_min;  ///< random placement region (with region_max)
  std::optional<Vec2> region_max;
  std::optional<double> yaw_deg;  ///< fixed yaw; default random (region) or 0 (at)
  /// Where the solid's centre lies in the object's frame (x along its heading) from `at`: a
  /// source model whose origin is not its footprint's centre keeps its own pose in `at`.
  Vec2 offset = Vec2::Zero();
  Vec3 size_min = Vec3::Zero();  ///< size range (kind-specific meaning, see docs/worlds.md)
  Vec3 size_max = Vec3::Zero();
  std::string variant;           ///< kind-specific: building burned|collapsed|collapsed_burned, ...
  std::string texture;           ///< texture override (default per kind)
  double tilt_max_deg = 0.0;     ///< random tilt (rods, poles, rocks)
  double burned_fraction = 0.4;  ///< burned share of a burned building's length (collapsed_burned: of its block)
  /// Look of the burned part: empty = flat black and textureless, else a texture name (e.g. the
  /// collapsed house's sooted brick, "burned").
  std::string burned_texture;
  double base_z_m = 0.0;  ///< height of the object's base
  /// "ruins": placed at the ruins built before (burned parts and collapsed buildings), not in a
  /// region — rods as reinforcement bars standing out of the ruins and their rubble.
  std::string near;

  /// The keys, each once with the values it accepts (`at`, `region`, `yaw_deg` and `size` are
  /// read in tools/config: optional or shorthand).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("kind", s.kind);
    v.key("name", s.name);
    v.key("count", s.count, Limits::range(1, 1000));
    v.key("offset", s.offset, Limits::range(-100.0, 100.0));
    v.key("size_min", s.size_min, Limits::nonNegative());
    v.key("size_max", s.size_max, Limits::nonNegative());
    v.key("variant", s.variant);
    v.key("texture", s.texture);
    v.key("tilt_max_deg", s.tilt_max_deg, Limits::range(0.0, 60.0));
    v.key("burned_fraction", s.burned_fraction, Limits::range(0.05, 0.95));
    v.key("burned_texture", s.burned_texture);
    v.key("base_z_m", s.base_z_m, Limits::any());
    v.key("near", s.near, Choices{"", "ruins"});
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// A rectangular chamber of a cave, carved out of solid rock up to its ceiling height.
struct CaveChamberSpec {
  Vec2 min = Vec2::Zero(), max = Vec2::Zero();
  double ceiling_m = 8.0;

  /// The keys, each once with the values it accepts.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("min", s.min, Limits::any());
    v.key("max", s.max, Limits::any());
    v.key("ceiling_m", s.ceiling_m, Limits{2.0, 1000.0, true, false});
  }
  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// A straight tunnel of a cave between two points.
struct CaveTunnelSpec {
  Vec2 from = Vec2::Zero(), to = Vec2::Zero();
  double width_m = 6.0;
  double ceiling_m = 6.0;

  /// The keys, each once with the values it accepts.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("from", s.from, Limits::any());
    v.key("to", s.to, Limits::any());
    v.key("width_m", s.width_m, Limits::range(2.0, 1000.0));
    v.key("ceiling_m", s.ceiling_m, Limits{2.0, 1000.0, true, false});
  }
  /// Records invalid fields.
  void validate(ConfigChecker& c) const { checkFields(*this, c); }
};

/// An enclosed cave: everything inside [min, max] is rock except chambers and tunnels.
struct CaveSpec {
  Vec2 min = Vec2::Zero(), max = Vec2::Zero();
  double rock_top_m = 20.0;  ///< height of the rock mass (ceiling top)
  double cell_m = 2.5;       ///< carving resolution
  std::vector<CaveChamberSpec> chambers;
  std::vector<CaveTunnelSpec> tunnels;
  std::string texture = "rock";

  /// The keys, each once with the values it accepts (the lists `chambers` and `tunnels` are read
  /// in tools/config, each element by its own table).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("min", s.min, Limits::any());
    v.key("max", s.max, Limits::any());
    v.key("rock_top_m", s.rock_top_m, Limits::positive());
    v.key("cell_m", s.cell_m, Limits::range(0.5, 10.0));
    v.key("texture", s.texture);
  }
  /// Records invalid fields (with each chamber's and tunnel's).
  void validate(ConfigChecker& c) const;
};

/// Where a world's imported files come from: a public repository at a commit. The files are
/// copied from a checkout by `msbench world import NAME --from CHECKOUT` into the world cache
/// (`sources/NAME/`), where generation reads them; msbench ships none of them.
struct SourceSpec {
  std::string repository;  ///< e.g. ctu-mrs/monospheres
  std::string commit;      ///< e.g. 43fca1f

  /// The keys, each once with the values it accepts.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("repository", s.repository);
    v.key("commit", s.commit);
  }
  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// A mesh from the world's source, placed as its Gazebo model places it (docs/worlds.md,
/// "Imported meshes"): collision and ground truth from convex pieces, looks from its materials.
struct MeshSpec {
  std::string file;               ///< path inside the source checkout
  std::string name;               ///< the source's name for it (e.g. the Gazebo model's)
  Vec3 at = Vec3::Zero();         ///< position of the mesh's origin
  double yaw_deg = 0.0;           ///< heading of the mesh's frame
  Vec3 scale = Vec3::Ones();      ///< the model's mesh scale
  std::string kind = "textured";  ///< ground-truth kind of its parts (terrain parts are ground)
  double slab_thickness_m =
      0.3;  ///< thickness of the slab under each triangle of a part that is neither convex nor terrain
  /// A procedural texture drawn (in world metres) where an image the mesh names is not in the
  /// imported source; empty: such a mesh is an error.
  std::string missing_texture;
  int max_texture_px = 2048;  ///< images are scaled down to this side (grey, as the camera sees)
  /// Not a key: the mesh is mirrored across its own x axis (a held-out world's mirror,
  /// sim/world/world_salt.h).
  bool mirrored = false;

  /// The keys, each once with the values it accepts.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("file", s.file);
    v.key("name", s.name);
    v.key("at", s.at, Limits::range(-1e4, 1e4));
    v.key("yaw_deg", s.yaw_deg, Limits::range(-360.0, 360.0));
    v.key("scale", s.scale, Limits::range(1e-6, 1e4));
    v.key("kind", s.kind, Choices{"textured", "textureless"});
    v.key("slab_thickness_m", s.slab_thickness_m, Limits::range(0.01, 10.0));
    v.key("missing_texture", s.missing_texture);
    v.key("max_texture_px", s.max_texture_px, Limits::range(16, 8192));
  }
  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// A whole world.
struct WorldSpec {
  std::string name;         ///< world name (folder under worlds/)
  std::string description;  ///< one line for `world list`
  /// The paper's Table I world this world is (the authors' files rebuilt or imported: suburb3 is
  /// "rooftops"); recorded in metrics.json as `paper_world`, so reports pair its runs with the
  /// paper's rows. Empty: none (a world named like a Table I world is that row by its name).
  std::string paper_world;
  uint64_t seed = 1;                    ///< placement seed
  Vec2 ground_size_m = Vec2(120, 120);  ///< ground plane extent, centred on the origin
  std::string ground_texture = "grass";
  Vec3 start_position_m = Vec3::Zero();  ///< vehicle start (on the ground: z = 0)
  double start_yaw_deg = 0.0;
  Aabb exploration_box;            ///< where exploration goals may lie
  double start_clearance_m = 6.0;  ///< free radius kept around the start
  double start_corridor_m = 0.0;   ///< length of the free corridor along the start heading (take-off direction)
  double start_corridor_half_width_m = 3.0;  ///< its half width
  int texture_px = 512;                      ///< texture resolution
  std::vector<ObjectGroupSpec> objects;
  std::optional<CaveSpec> cave;
  bool ground_enabled = true;        ///< a ground plane (false: an imported terrain is the ground)
  std::optional<SourceSpec> source;  ///< where `meshes` come from
  std::vector<MeshSpec> meshes;      ///< imported meshes
  /// Not a key: the directory the imported files are read from (the world cache's
  /// sources/NAME/, set where the spec is resolved).
  std::string source_dir;
  /// Not a key: the procedural textures' seed (0: the world's own textures; a held-out world's
  /// is drawn from its salt, sim/world/world_salt.h).
  uint64_t texture_seed = 0;
  /// Not a key: the outdoor sun's direction (a held-out world's mirror mirrors it, so that every
  /// face is lit as its mirror image was).
  Vec3 sun_direction = Vec3(0.62, 0.47, -0.63);

  /// The top-level keys, each once with the values it accepts (`ground`, `start`,
  /// `exploration_box`, `objects` and `cave` are read in tools/config).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("name", s.name);
    v.key("description", s.description);
    v.key("paper_world", s.paper_world, Choices{"", "urban", "cave", "rooftops", "sparse"});
    v.key("seed", s.seed, Limits::nonNegative());
    v.key("start_clearance_m", s.start_clearance_m, Limits::nonNegative());
    v.key("start_corridor_m", s.start_corridor_m, Limits::nonNegative());
    v.key("start_corridor_half_width_m", s.start_corridor_half_width_m, Limits::positive());
    v.key("texture_px", s.texture_px, Limits::range(128, 1024));
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

}  // namespace msb
