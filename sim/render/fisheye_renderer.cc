#include "sim/render/fisheye_renderer.h"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "core/common/wall_time.h"

namespace msb {

void FisheyeRendererConfig::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.nested("conditions", conditions);
}

namespace {

// Face frames (columns: face x right, face y down, face z normal) in the camera optical frame.
std::vector<CubeFace> nominalFaces() {
  auto face = [](const char* name, Vec3 x, Vec3 y, Vec3 z) {
    CubeFace f;
    f.name = name;
    f.R_C_F.col(0) = x;
    f.R_C_F.col(1) = y;
    f.R_C_F.col(2) = z;
    return f;
  };
  return {face("front", {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), face("right", {0, 0, -1}, {0, 1, 0}, {1, 0, 0}),
          face("left", {0, 0, 1}, {0, 1, 0}, {-1, 0, 0}), face("down", {1, 0, 0}, {0, 0, -1}, {0, 1, 0}),
          face("up", {1, 0, 0}, {0, 0, 1}, {0, -1, 0})};
}

// Index of the cube face whose normal is closest to the direction.
int faceOf(const std::vector<CubeFace>& faces, const Vec3& d) {
  int best = 0;
  double best_z = -2.0;
  for (size_t i = 0; i < faces.size(); ++i) {
    const double z = faces[i].R_C_F.col(2).dot(d);
    if (z > best_z) best_z = z, best = static_cast<int>(i);
  }
  return best;
}

}  // namespace

bool modelRendersGrey(const mjModel* m) {
  const auto grey3 = [](const float* c) { return c[0] == c[1] && c[0] == c[2]; };
  for (int g = 0; g < m->ngeom; ++g)
    if (!grey3(m->geom_rgba + 4 * g)) return false;
  for (int i = 0; i < m->nmat; ++i)
    if (!grey3(m->mat_rgba + 4 * i)) return false;
  for (int i = 0; i < m->nskin; ++i)
    if (!grey3(m->skin_rgba + 4 * i)) return false;
  for (int l = 0; l < m->nlight; ++l)
    if (!grey3(m->light_ambient + 3 * l) || !grey3(m->light_diffuse + 3 * l) || !grey3(m->light_specular + 3 * l))
      return false;
  const mjVisual& v = m->vis;
  if (!grey3(v.headlight.ambient) || !grey3(v.headlight.diffuse) || !grey3(v.headlight.specular) ||
      !grey3(v.rgba.fog) || !grey3(v.rgba.haze))
    return false;
  for (int i = 0; i + 2 < m->ntexdata; i += 3)
    if (m->tex_rgb[i] != m->tex_rgb[i + 1] || m->tex_rgb[i] != m->tex_rgb[i + 2]) return false;
  return true;
}

FisheyeRenderer::FisheyeRenderer(const FisheyeRendererConfig& config, const FisheyeCamera& camera, const mjModel* model)
    : config_(checkValid(config)),
      camera_(camera),
      model_copy_(mj_copyModel(nullptr, model), mj_deleteModel),
      model_(model_copy_.get()) {
  if (!model_) throw std::runtime_error("MuJoCo: could not copy the model for rendering");
  face_focal_px_ = config_.face_focal_ratio * camera_.fx();
  buildFacesAndLut();

  configureRenderModel();

  // GL context (tiny default framebuffer: MuJoCo renders into its off-screen FBO).
  context_ = makeOsMesaContext(64, 64);
  mjv_defaultScene(&scene_);
  mjv_makeScene(model_, &scene_, std::max(1000, 2 * model_->ngeom));
  mjr_defaultContext(&mjr_context_);
  mjr_makeContext(model_, &mjr_context_, mjFONTSCALE_50);
  if (mjr_context_.offWidth < atlas_width_ || mjr_context_.offHeight < atlas_height_)
    throw std::runtime_error("MuJoCo off-screen buffer smaller than the face atlas");
  // Texture minification: MuJoCo uploads every texture with trilinear filtering; by default
  // only the nearest mip level is sampled (bilinear within it), which saves llvmpipe about a
  // fifth of the frame with the same sharpness and tracking (docs/performance.md).
  if (!config_.trilinear_textures) {
    for (int i = 0; i < mjr_context_.ntexture; ++i) {
      const GLenum target = mjr_context_.textureType[i] == mjTEXTURE_2D ? GL_TEXTURE_2D : GL_TEXTURE_CUBE_MAP;
      glBindTexture(target, mjr_context_.texture[i]);
      glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
    }
  }
  if (config_.single_channel_textures) storeGreyTexturesAsLuminance();
  mjr_setBuffer(mjFB_OFFSCREEN, &mjr_context_);
  if (config_.framebuffer_per_face) makeFaceFramebuffers();
  // Fog by distance from the eye, not by depth along each cube face's axis (which would differ
  // between faces and leave seams); MuJoCo sets the rest of the fog state on every render.
  if (config_.conditions.fog_end_m > 0) glFogi(GL_FOG_DISTANCE_MODE_NV, GL_EYE_RADIAL_NV);

  mjv_defaultOption(&options_);
  // Geom groups 0-2 are the visible world; 3 is the vehicle, 4 collision-only geoms.
  for (int g = 0; g < mjNGROUP; ++g) options_.geomgroup[g] = g <= config_.max_visible_geom_group;
  options_.geomgroup[kSkyGeomGroup] = config_.sky ? 1 : 0;  // the world's sky planes, if any
  // Only geoms: no sites, joints, tendons or other decorations.
  for (int g = 0; g < mjNGROUP; ++g) options_.sitegroup[g] = 0;
  for (int f = 0; f < mjNVISFLAG; ++f) options_.flags[f] = 0;
  options_.flags[mjVIS_STATIC] = 1;
  options_.flags[mjVIS_TEXTURE] = 1;
  mjv_defaultFreeCamera(model_, &free_camera_);
  for (int f = 0; f < mjNRNDFLAG; ++f) scene_.flags[f] = 0;
  scene_.flags[mjRND_CULL_FACE] = 1;
  scene_.flags[mjRND_SKYBOX] = 0;
  scene_.flags[mjRND_FOG] = config_.conditions.fog_end_m > 0 ? 1 : 0;

  // Beyond the far clip: the fog colour in fog, else the sky's colour if the world has a drawn
  // sky (saturated white, or the conditions' sky grey), else black (caves: no sky).
  bool has_sky = false;
  for (int g = 0; g < model_->ngeom; ++g) has_sky = has_sky || model_->geom_group[g] == kSkyGeomGroup;
  const RenderConditions& cond = config_.conditions;
  for (int k = 0; k < 3; ++k)
    backdrop_[k] = cond.fog_end_m > 0                ? static_cast<float>(cond.fog_colour[k])
                   : !(config_.sky && has_sky)       ? 0.0f
                   : std::isnan(cond.sky_brightness) ? 1.0f
                                                     : static_cast<float>(cond.sky_brightness);
}

void FisheyeRenderer::configureRenderModel() {
  // Benchmark visual settings: no MSAA, coarse tessellation, ambient-only headlight.
  model_->vis.global.offwidth = atlas_width_;
  model_->vis.global.offheight = atlas_height_;
  model_->vis.quality.offsamples = 0;
  model_->vis.quality.numslices = config_.tessellation_slices;
  model_->vis.quality.numstacks = config_.tessellation_stacks;
  model_->vis.headlight.active = 1;
  // World lights (a directional sun) only with the `sun` switch: diffuse shading from a
  // world-fixed direction is the same in every cube face, so it adds no seams.
  // Worlds without lights (caves) keep the bright ambient headlight.
  for (int l = 0; l < model_->nlight; ++l) model_->light_active[l] = config_.sun ? 1 : 0;
  const RenderConditions& cond = config_.conditions;
  const double ambient = !std::isnan(cond.ambient)           ? cond.ambient
                         : config_.sun && model_->nlight > 0 ? config_.sun_ambient
                                                             : config_.ambient;
  // Conditions: the sun's direction (applied to the scene's lights every frame), intensity and
  // colour; the sky's grey level; fog (docs/conditions.md).
  for (int l = 0; l < model_->nlight; ++l) {
    if (!model_->light_directional[l]) continue;
    if (!std::isnan(cond.sun_elevation_deg) || !std::isnan(cond.sun_azimuth_deg)) {
      const Vec3 to_sun =
          -Vec3(model_->light_dir[3 * l], model_->light_dir[3 * l + 1], model_->light_dir[3 * l + 2]).normalized();
      const double e = std::isnan(cond.sun_elevation_deg) ? std::asin(to_sun.z()) : cond.sun_elevation_deg * M_PI / 180;
      const double a =
          std::isnan(cond.sun_azimuth_deg) ? std::atan2(to_sun.y(), to_sun.x()) : cond.sun_azimuth_deg * M_PI / 180;
      sun_direction_ = -Vec3(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
    }
    for (int k = 0; k < 3; ++k) {
      const double intensity = std::isnan(cond.sun_intensity) ? model_->light_diffuse[3 * l + k] : cond.sun_intensity;
      model_->light_diffuse[3 * l + k] = static_cast<float>(intensity * cond.sun_colour[k]);
    }
  }
  if (!std::isnan(cond.sky_brightness)) {
    // Self-lit sky planes: emission 1 plus the ambient and the sun's diffuse term, which differs
    // from plane to plane (their normals differ); each plane's colour is scaled so that the sum
    // is the grey level on every plane, without seams.
    Vec3 to_sun = Vec3::Zero(), sun_diffuse = Vec3::Zero();
    for (int l = 0; l < model_->nlight; ++l) {
      if (!model_->light_directional[l] || !model_->light_active[l]) continue;
      to_sun = sun_direction_
                   ? Vec3(-*sun_direction_)
                   : Vec3(-Vec3(model_->light_dir[3 * l], model_->light_dir[3 * l + 1], model_->light_dir[3 * l + 2])
                               .normalized());
      sun_diffuse =
          Vec3(model_->light_diffuse[3 * l], model_->light_diffuse[3 * l + 1], model_->light_diffuse[3 * l + 2]);
    }
    for (int g = 0; g < model_->ngeom; ++g) {
      if (model_->geom_group[g] != kSkyGeomGroup) continue;
      const mjtNum* q = model_->geom_quat + 4 * g;  // w, x, y, z: the plane faces its local +z
      const Vec3 normal(2 * (q[1] * q[3] + q[0] * q[2]), 2 * (q[2] * q[3] - q[0] * q[1]),
                        1 - 2 * (q[1] * q[1] + q[2] * q[2]));
      const double lit = std::max(0.0, normal.dot(to_sun));
      float* rgba = model_->geom_rgba + 4 * g;
      for (int k = 0; k < 3; ++k)
        rgba[k] = static_cast<float>(cond.sky_brightness / (1.0 + ambient + lit * sun_diffuse[k]));
      // A geom colour other than MuJoCo's default overrides its material's; emission stays 1.
      if (model_->geom_matid[g] >= 0) model_->mat_emission[model_->geom_matid[g]] = 1.0f;
    }
  }
  if (cond.fog_end_m > 0) {
    // MuJoCo's fog distances are fractions of the model extent; GL fog is linear in eye depth.
    const double extent = std::max(model_->stat.extent, 1e-6);
    model_->vis.map.fogstart = static_cast<float>(cond.fog_start_m / extent);
    model_->vis.map.fogend = static_cast<float>(cond.fog_end_m / extent);
    for (int k = 0; k < 3; ++k) model_->vis.rgba.fog[k] = static_cast<float>(cond.fog_colour[k]);
    model_->vis.rgba.fog[3] = 1.0f;
  }
  for (int i = 0; i < 3; ++i) {
    model_->vis.headlight.ambient[i] = static_cast<float>(ambient);
    model_->vis.headlight.diffuse[i] = 0.0f;
    model_->vis.headlight.specular[i] = 0.0f;
  }
  // Coarse plane grid: for planes the third size is only the rendering grid spacing.
  for (int g = 0; g < model_->ngeom; ++g)
    if (model_->geom_type[g] == mjGEOM_PLANE)
      model_->geom_size[3 * g + 2] = std::max(model_->geom_size[3 * g + 2], config_.plane_grid_m);
}

FisheyeRenderer::~FisheyeRenderer() {
  context_->makeCurrent();  // GL objects belong to this renderer's context
  if (!face_fbo_.empty()) {
    glDeleteFramebuffers(GLsizei(face_fbo_.size()), face_fbo_.data());
    glDeleteRenderbuffers(GLsizei(face_colour_rb_.size()), face_colour_rb_.data());
    glDeleteRenderbuffers(GLsizei(face_depth_rb_.size()), face_depth_rb_.data());
  }
  mjr_freeContext(&mjr_context_);
  mjv_freeScene(&scene_);
}

void FisheyeRenderer::storeGreyTexturesAsLuminance() {
  // MuJoCo uploads every texture as RGB with its mip chain. A grey texture (every texel of
  // every level has R = G = B) is read back level by level and stored again as one-byte
  // luminance with the same texel values: the sampler returns (L, L, L, 1) as before, from a
  // quarter of the memory.
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  std::vector<uint8_t> rgb;
  for (int i = 0; i < mjr_context_.ntexture; ++i) {
    const bool cube = mjr_context_.textureType[i] != mjTEXTURE_2D;
    const GLenum target = cube ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D;
    glBindTexture(target, mjr_context_.texture[i]);
    struct Level {
      GLenum image_target;
      int level, width, height;
      std::vector<uint8_t> luminance;
    };
    std::vector<Level> levels;
    bool grey = true;
    for (int side = 0; side < (cube ? 6 : 1) && grey; ++side) {
      const GLenum image_target = cube ? GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + side) : GL_TEXTURE_2D;
      for (int level = 0; grey; ++level) {
        GLint w = 0, h = 0;
        glGetTexLevelParameteriv(image_target, level, GL_TEXTURE_WIDTH, &w);
        glGetTexLevelParameteriv(image_target, level, GL_TEXTURE_HEIGHT, &h);
        if (w <= 0 || h <= 0) break;
        rgb.resize(size_t(w) * h * 3);
        glGetTexImage(image_target, level, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
        Level l{image_target, level, w, h, std::vector<uint8_t>(size_t(w) * h)};
        for (size_t p = 0; p < l.luminance.size() && grey; ++p) {
          grey = rgb[3 * p] == rgb[3 * p + 1] && rgb[3 * p] == rgb[3 * p + 2];
          l.luminance[p] = rgb[3 * p];
        }
        levels.push_back(std::move(l));
      }
    }
    if (!grey || levels.empty()) continue;
    for (const Level& l : levels)
      glTexImage2D(l.image_target, l.level, GL_LUMINANCE8, l.width, l.height, 0, GL_LUMINANCE, GL_UNSIGNED_BYTE,
                   l.luminance.data());
    ++luminance_textures_;
  }
}

void FisheyeRenderer::makeFaceFramebuffers() {
  // MuJoCo clears the viewport it renders into with the scissor test on; Mesa turns a clear
  // that does not cover the whole framebuffer into a drawn quad, which llvmpipe rasterises
  // like any geometry (about a tenth of the frame). A framebuffer the size of the face makes
  // the same clear a whole-buffer clear. Same formats as MuJoCo's off-screen buffer, so the
  // same colour and depth precision.
  GLint colour_format = GL_RGBA8, depth_format = GL_DEPTH24_STENCIL8;
  glBindRenderbuffer(GL_RENDERBUFFER, mjr_context_.offColor);
  glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_INTERNAL_FORMAT, &colour_format);
  glBindRenderbuffer(GL_RENDERBUFFER, mjr_context_.offDepthStencil);
  glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_INTERNAL_FORMAT, &depth_format);
  // A grey world renders R = G = B in every pixel (each channel is computed alike from equal
  // inputs), so one channel holds the whole image: a quarter of the colour memory to shade,
  // clear and read back, and no colour-to-grey conversion.
  if (config_.single_channel_framebuffer && modelRendersGrey(model_)) {
    colour_format = GL_R8;
    single_channel_framebuffer_ = true;
  }
  const GLsizei n = GLsizei(faces_.size());
  face_fbo_.resize(n), face_colour_rb_.resize(n), face_depth_rb_.resize(n);
  glGenFramebuffers(n, face_fbo_.data());
  glGenRenderbuffers(n, face_colour_rb_.data());
  glGenRenderbuffers(n, face_depth_rb_.data());
  for (GLsizei i = 0; i < n; ++i) {
    glBindFramebuffer(GL_FRAMEBUFFER, face_fbo_[i]);
    glBindRenderbuffer(GL_RENDERBUFFER, face_colour_rb_[i]);
    glRenderbufferStorage(GL_RENDERBUFFER, GLenum(colour_format), faces_[i].width, faces_[i].height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, face_colour_rb_[i]);
    glBindRenderbuffer(GL_RENDERBUFFER, face_depth_rb_[i]);
    glRenderbufferStorage(GL_RENDERBUFFER, GLenum(depth_format), faces_[i].width, faces_[i].height);
    const GLenum attachment = depth_format == GL_DEPTH24_STENCIL8 || depth_format == GL_DEPTH32F_STENCIL8
                                  ? GL_DEPTH_STENCIL_ATTACHMENT
                                  : GL_DEPTH_ATTACHMENT;
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, attachment, GL_RENDERBUFFER, face_depth_rb_[i]);
    glDrawBuffer(GL_COLOR_ATTACHMENT0);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("GL: incomplete cube-face framebuffer");
  }
  mjr_restoreBuffer(&mjr_context_);
}

long FisheyeRenderer::renderedPixels() const {
  long n = 0;
  for (const auto& f : faces_) n += static_cast<long>(f.width) * f.height;
  return n;
}

void FisheyeRenderer::buildFacesAndLut() {
  const int W = camera_.width(), H = camera_.height();
  const double ff = face_focal_px_;
  std::vector<CubeFace> all = nominalFaces();

  // Pass 1: which face each in-FoV pixel samples, and the tangent bounds used per face.
  std::vector<int> pixel_face(static_cast<size_t>(W) * H, -1);
  std::vector<Vec2> pixel_tan(static_cast<size_t>(W) * H);
  std::vector<std::array<double, 4>> bounds(all.size(), {1e9, -1e9, 1e9, -1e9});
  for (int v = 0; v < H; ++v) {
    for (int u = 0; u < W; ++u) {
      const Vec2 px(u, v);
      if (!camera_.pixelInFov(px)) continue;
      const Vec3 d = camera_.unproject(px);
      const int f = faceOf(all, d);
      const Vec3 dF = all[f].R_C_F.transpose() * d;
      const Vec2 t(dF.x() / dF.z(), dF.y() / dF.z());
      const size_t i = static_cast<size_t>(v) * W + u;
      pixel_face[i] = f;
      pixel_tan[i] = t;
      auto& b = bounds[f];
      b = {std::min(b[0], t.x()), std::max(b[1], t.x()), std::min(b[2], t.y()), std::max(b[3], t.y())};
    }
  }

  // Rendered rectangle per used face: the bounds plus a 2-pixel bilinear margin.
  const double margin = 2.0 / ff;
  std::vector<int> face_index(all.size(), -1);
  for (size_t f = 0; f < all.size(); ++f) {
    if (bounds[f][0] > bounds[f][1]) continue;
    CubeFace face = all[f];
    face.tan_x0 = bounds[f][0] - margin;
    face.tan_y0 = bounds[f][2] - margin;
    face.width = static_cast<int>(std::ceil((bounds[f][1] + margin - face.tan_x0) * ff));
    face.height = static_cast<int>(std::ceil((bounds[f][3] + margin - face.tan_y0) * ff));
    face_index[f] = static_cast<int>(faces_.size());
    faces_.push_back(face);
  }

  // Shelf packing of the rectangles into one atlas (tallest first, 2-pixel gaps).
  std::vector<size_t> order(faces_.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return faces_[a].height > faces_[b].height; });
  int max_w = 0;
  long area = 0;
  for (const auto& f : faces_) max_w = std::max(max_w, f.width), area += long{f.width} * f.height;
  const int shelf_limit = std::max(max_w, static_cast<int>(std::sqrt(double(area)) * 1.3));
  int x = 0, y = 0, shelf_h = 0;
  for (size_t i : order) {
    auto& f = faces_[i];
    if (x > 0 && x + f.width > shelf_limit) y += shelf_h + 2, x = 0, shelf_h = 0;
    f.atlas_x = x;
    f.atlas_y = y;
    x += f.width + 2;
    shelf_h = std::max(shelf_h, f.height);
    atlas_width_ = std::max(atlas_width_, x);
  }
  atlas_height_ = y + shelf_h;

  // Pass 2: lookup table from fisheye pixels to atlas pixels (GL rows, bottom first).
  cv::Mat map_x(H, W, CV_32F, cv::Scalar(-100.0f)), map_y(H, W, CV_32F, cv::Scalar(-100.0f));
  for (int v = 0; v < H; ++v) {
    for (int u = 0; u < W; ++u) {
      const size_t i = static_cast<size_t>(v) * W + u;
      if (pixel_face[i] < 0) continue;
      const CubeFace& f = faces_[face_index[pixel_face[i]]];
      const double tan_y1 = f.tan_y0 + f.height / ff;
      map_x.at<float>(v, u) = static_cast<float>(f.atlas_x + (pixel_tan[i].x() - f.tan_x0) * ff - 0.5);
      map_y.at<float>(v, u) = static_cast<float>(f.atlas_y + (tan_y1 - pixel_tan[i].y()) * ff - 0.5);
    }
  }
  cv::Mat map_xy, map_interp;
  cv::convertMaps(map_x, map_y, map_xy, map_interp, CV_16SC2);
  remap_ = FixedPointRemap(map_xy, map_interp, cv::Size(atlas_width_, atlas_height_));
}

void FisheyeRenderer::cullToFace(const Mat3& R_W_F, const Vec3& eye, double tx0, double tx1, double ty0, double ty1) {
  // The frustum's side planes in the face frame (inward normals through the eye): x >= tx0 z,
  // x <= tx1 z, y >= ty0 z, y <= ty1 z; and the half-space in front of the eye.
  const Vec3 normals[5] = {Vec3(1, 0, -tx0).normalized(), Vec3(-1, 0, tx1).normalized(), Vec3(0, 1, -ty0).normalized(),
                           Vec3(0, -1, ty1).normalized(), Vec3(0, 0, 1)};
  int kept = 0;
  for (const mjvGeom& g : scene_geoms_) {
    bool visible = true;
    if (g.modelrbound > 0) {
      const Vec3 p = R_W_F.transpose() * (Vec3(g.pos[0], g.pos[1], g.pos[2]) - eye);
      // Margin: float positions and bounds.
      const double r = 1.001 * double(g.modelrbound) + 1e-3;
      for (const Vec3& nrm : normals) visible = visible && nrm.dot(p) >= -r;
    } else if (g.type == mjGEOM_PLANE && g.size[0] > 0 && g.size[1] > 0) {
      // A finite plane (ground, sky) has no bound: it is drawn as its rectangle, which is
      // dropped when all four corners lie outside one side of the frustum.
      const Vec3 c = R_W_F.transpose() * (Vec3(g.pos[0], g.pos[1], g.pos[2]) - eye);
      const Vec3 ax = R_W_F.transpose() * Vec3(g.mat[0], g.mat[3], g.mat[6]) * double(g.size[0]);
      const Vec3 ay = R_W_F.transpose() * Vec3(g.mat[1], g.mat[4], g.mat[7]) * double(g.size[1]);
      const double margin = 1e-3 * (1.0 + c.norm() + ax.norm() + ay.norm());
      for (const Vec3& nrm : normals) {
        bool all_outside = true;
        for (const double sx : {-1.0, 1.0})
          for (const double sy : {-1.0, 1.0}) all_outside = all_outside && nrm.dot(c + sx * ax + sy * ay) < -margin;
        visible = visible && !all_outside;
      }
    }
    if (visible) scene_.geoms[kept++] = g;
  }
  scene_.ngeom = kept;
}

void FisheyeRenderer::paintBeyondClip(int x, int y, int width, int height) {
  // A quad at the far plane, drawn only where the depth buffer still holds its cleared 1.0: the
  // pixels nothing was drawn into (beyond the clip, or open sky without sky planes) take the
  // backdrop colour instead of MuJoCo's black clear colour.
  glPushAttrib(GL_ALL_ATTRIB_BITS);
  glViewport(x, y, width, height);
  glDisable(GL_LIGHTING);
  glDisable(GL_TEXTURE_2D);
  glDisable(GL_FOG);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_STENCIL_TEST);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glMatrixMode(GL_PROJECTION);
  glPushMatrix();
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glPushMatrix();
  glLoadIdentity();
  glColor4f(backdrop_[0], backdrop_[1], backdrop_[2], 1.0f);
  glBegin(GL_QUADS);
  glVertex3f(-1.0f, -1.0f, 1.0f);
  glVertex3f(1.0f, -1.0f, 1.0f);
  glVertex3f(1.0f, 1.0f, 1.0f);
  glVertex3f(-1.0f, 1.0f, 1.0f);
  glEnd();
  glPopMatrix();
  glMatrixMode(GL_PROJECTION);
  glPopMatrix();
  glPopAttrib();
}

void FisheyeRenderer::render(const mjData* data, const Pose& T_W_C, CameraFrame* frame, RenderTiming* timing) {
  RenderTiming t;
  auto t0 = WallClock::now();
  updateScene(data);
  t.scene_ms = msSince(t0);
  // Render every face rectangle into its atlas viewport with an off-centre frustum.
  t0 = WallClock::now();
  renderFaces(T_W_C);
  glFinish();
  t.render_ms = msSince(t0);
  // Read-back of the atlas: at once, or face by face into its place.
  t0 = WallClock::now();
  const bool red_only = readBackAtlas();
  t.readback_ms = msSince(t0);
  // Grey conversion and fisheye remap.
  t0 = WallClock::now();
  remapInto(frame, red_only);
  t.remap_ms = msSince(t0);
  if (timing) *timing = t;
}

void FisheyeRenderer::updateScene(const mjData* data) {
  context_->makeCurrent();
  mjv_updateScene(model_, const_cast<mjData*>(data), &options_, nullptr, &free_camera_, mjCAT_ALL, &scene_);
  if (sun_direction_)
    for (int i = 0; i < scene_.nlight; ++i)
      if (scene_.lights[i].directional && !scene_.lights[i].headlight)
        for (int k = 0; k < 3; ++k) scene_.lights[i].dir[k] = static_cast<float>((*sun_direction_)[k]);
  if (config_.cull_per_face) scene_geoms_.assign(scene_.geoms, scene_.geoms + scene_.ngeom);
}

void FisheyeRenderer::renderFaces(const Pose& T_W_C) {
  const float n = static_cast<float>(config_.near_clip_m);
  const Mat3 R_W_C = T_W_C.linear();
  const Vec3 pos = T_W_C.translation();
  drawn_geoms_ = 0;
  for (const auto& f : faces_) {
    const Mat3 R_W_F = R_W_C * f.R_C_F;
    const Vec3 fwd = R_W_F.col(2), up = -R_W_F.col(1);
    const double x1 = f.tan_x0 + f.width / face_focal_px_;
    const double y1 = f.tan_y0 + f.height / face_focal_px_;
    for (int c = 0; c < 2; ++c) {
      mjvGLCamera& cam = scene_.camera[c];
      for (int k = 0; k < 3; ++k) {
        cam.pos[k] = static_cast<float>(pos[k]);
        cam.forward[k] = static_cast<float>(fwd[k]);
        cam.up[k] = static_cast<float>(up[k]);
      }
      cam.frustum_center = static_cast<float>(n * 0.5 * (f.tan_x0 + x1));
      cam.frustum_bottom = static_cast<float>(-n * y1);
      cam.frustum_top = static_cast<float>(-n * f.tan_y0);
      cam.frustum_near = n;
      cam.frustum_far = static_cast<float>(camera_.config().clip_far_m);
    }
    if (config_.cull_per_face) cullToFace(R_W_F, pos, f.tan_x0, x1, f.tan_y0, y1);
    drawn_geoms_ += scene_.ngeom;
    if (face_fbo_.empty()) {
      mjr_render(mjrRect{f.atlas_x, f.atlas_y, f.width, f.height}, &scene_, &mjr_context_);
      paintBeyondClip(f.atlas_x, f.atlas_y, f.width, f.height);
    } else {
      // mjr_render draws into the bound framebuffer and rebinds its own when done.
      glBindFramebuffer(GL_FRAMEBUFFER, face_fbo_[&f - faces_.data()]);
      // MuJoCo clears colour and depth only; llvmpipe keeps the stencil bits of the packed
      // depth-stencil buffer with a masked per-pixel loop (~1 ms a frame). Cleared here too, the
      // two clears fold into one whole-word fill (no draw between them). The stencil is unused
      // (no reflections), so the pixels are the same.
      glDisable(GL_SCISSOR_TEST);
      glClear(GL_STENCIL_BUFFER_BIT);
      mjr_render(mjrRect{0, 0, f.width, f.height}, &scene_, &mjr_context_);
      glBindFramebuffer(GL_FRAMEBUFFER, face_fbo_[&f - faces_.data()]);
      paintBeyondClip(0, 0, f.width, f.height);
    }
  }
}

bool FisheyeRenderer::readBackAtlas() {
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  const bool red_only = config_.read_red_channel_only || single_channel_framebuffer_;
  cv::Mat& atlas = red_only ? atlas_grey_ : atlas_raw_;
  if (atlas.rows != atlas_height_ || atlas.cols != atlas_width_) {
    // Zero once: the gaps between faces are never drawn (per-face framebuffers) or cleared.
    atlas = cv::Mat::zeros(atlas_height_, atlas_width_, red_only ? CV_8UC1 : CV_8UC4);
  }
  const GLenum format = red_only ? GL_RED : GL_RGBA;
  if (face_fbo_.empty()) {
    glReadPixels(0, 0, atlas_width_, atlas_height_, format, GL_UNSIGNED_BYTE, atlas.data);
  } else {
    glPixelStorei(GL_PACK_ROW_LENGTH, atlas_width_);
    for (size_t i = 0; i < faces_.size(); ++i) {
      const CubeFace& f = faces_[i];
      glBindFramebuffer(GL_READ_FRAMEBUFFER, face_fbo_[i]);
      glReadPixels(0, 0, f.width, f.height, format, GL_UNSIGNED_BYTE, atlas.ptr(f.atlas_y, f.atlas_x));
    }
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    mjr_restoreBuffer(&mjr_context_);
  }
  return red_only;
}

void FisheyeRenderer::remapInto(CameraFrame* frame, bool red_only) {
  if (!red_only) cv::cvtColor(atlas_raw_, atlas_grey_, cv::COLOR_RGBA2GRAY);
  remap_.apply(atlas_grey_, fisheye_);
  frame->width = fisheye_.cols;
  frame->height = fisheye_.rows;
  frame->pixels.assign(fisheye_.datastart, fisheye_.dataend);
}

}  // namespace msb
