// rrc_png_io: PNG writing (atomic) and reading through OpenImageIO.
#include "png_io.h"

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <memory>
#include <random>
#include <system_error>

namespace fs = std::filesystem;

namespace rrc_png {

namespace {

std::string temporary_name_for(const fs::path& target) {
    static thread_local std::mt19937_64 rng{std::random_device{}()};
    const char* hex = "0123456789abcdef";
    std::string suffix;
    std::uint64_t r = rng();
    for (int i = 0; i < 12; ++i, r >>= 4) suffix += hex[r & 15];
    return (target.parent_path() / ("." + target.filename().string() + ".tmp-" + suffix)).string();
}

}  // namespace

void write_png(const std::string& path, const RgbImage& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgb.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3)
        throw PngError(path + ": cannot write an RGB image of " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                       " with " + std::to_string(image.rgb.size()) + " bytes");
    const fs::path target(path);
    std::error_code ec;
    if (target.filename().empty() || fs::is_directory(target, ec)) throw PngError(path + ": cannot write: not a file name");
    const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    if (!fs::is_directory(dir, ec)) throw PngError(path + ": cannot write: directory '" + dir.string() + "' does not exist");
    const std::string tmp = temporary_name_for(target);
    auto out = OIIO::ImageOutput::create("png");
    if (!out) throw PngError(path + ": OpenImageIO has no PNG writer: " + OIIO::geterror());
    OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
    bool ok = out->open(tmp, spec) && out->write_image(OIIO::TypeDesc::UINT8, image.rgb.data());
    ok = out->close() && ok;
    if (!ok) {
        const std::string why = out->geterror();
        fs::remove(tmp, ec);
        throw PngError(path + ": cannot write: " + why);
    }
    fs::rename(tmp, target, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw PngError(path + ": cannot write: " + ec.message());
    }
}

RgbImage read_png(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw PngError(path + ": cannot read: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    RgbImage img;
    img.width = spec.width;
    img.height = spec.height;
    img.rgb.assign(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) * 3, 0);
    const bool ok = in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, img.rgb.data());
    const std::string why = in->geterror();
    in->close();
    if (!ok) throw PngError(path + ": cannot read: " + why);
    return img;
}

}  // namespace rrc_png
