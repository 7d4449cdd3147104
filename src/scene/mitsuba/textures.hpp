// Mitsuba 3's texture plugins, `bitmap` and `checkerboard`, as wavepath
// textures (scene/texture.hpp), for the BSDF parameters that take one.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "scene/mitsuba/xml_reader.hpp"
#include "scene/texture.hpp"

namespace wp::mitsuba {

// The textures a scene's BSDFs use, in order of first use; each image file
// is decoded once however often it is named.
class TextureTable {
  public:
    // Reads `texture` (a <texture> object: bitmap or checkerboard) and
    // returns its number k + 1 in textures(). Throws SceneError naming the
    // element for an unknown plugin or parameter, a missing or undecodable
    // file.
    std::uint32_t add(const Object& texture);

    const std::vector<Texture>& textures() const { return textures_; }
    std::vector<Texture> take() { return std::move(textures_); }

  private:
    std::vector<Texture> textures_;
    std::map<const Object*, std::uint32_t> numbers_;
    std::map<std::pair<std::string, bool>, std::shared_ptr<const TextureImage>> images_;
};

} // namespace wp::mitsuba
