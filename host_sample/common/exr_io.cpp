// rrc_exr_io: OpenEXR 3.1 reading (checked) and writing (atomic).
#include "exr_io.h"

#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfCheckFile.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputPart.h>
#include <ImfMultiPartInputFile.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfStdIO.h>
#include <ImfStringAttribute.h>
#include <ImfThreading.h>
#include <ImfVersion.h>
#include <openexr.h>

#include <Imath/half.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <system_error>

namespace fs = std::filesystem;

namespace rrc_exr {

ExrError::ExrError(const std::string& path, const std::string& message) : std::runtime_error(path + ": " + message), path_(path) {}

bool ExrImage::has(const std::string& name) const { return channels.count(name) != 0 || uint_channels.count(name) != 0; }

const std::vector<float>* ExrImage::find(const std::string& name) const {
    auto it = channels.find(name);
    return it == channels.end() ? nullptr : &it->second;
}

std::vector<float> ExrImage::as_float(const std::string& name, const std::string& path) const {
    if (auto it = channels.find(name); it != channels.end()) return it->second;
    if (auto it = uint_channels.find(name); it != uint_channels.end()) return std::vector<float>(it->second.begin(), it->second.end());
    throw ExrError(path, "missing channel '" + name + "'");
}

std::size_t ExrImage::pixel_count() const {
    if (width <= 0 || height <= 0) return 0;
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
}

bool ExrInfo::has(const std::string& name) const {
    return std::any_of(channels.begin(), channels.end(), [&](const ExrChannelInfo& c) { return c.name == name; });
}

namespace {

// The largest image we agree to decode (pixels); beyond it a "valid" header
// is far more likely corrupt than real.  16384^2 is rrc's own limit.
constexpr std::int64_t kMaxPixels = std::int64_t(16384) * 16384;

// A header can promise far more pixels than its file holds (a 684-byte file
// claiming 10 channels of 51380225x3 passes checkOpenEXRFile, which skips
// large images when asked to save memory, and would make read_exr allocate
// 6 GB).  Decoded float data beyond kMaxCompressionRatio times the file size
// (deflate's limit is ~1032:1) and beyond kMinDecodeBudget is refused before
// anything is allocated.
constexpr std::uint64_t kMaxCompressionRatio = 4096;
constexpr std::uint64_t kMinDecodeBudget = std::uint64_t(256) << 20;

std::string errno_text(int err) { return std::error_code(err, std::generic_category()).message(); }

// Refuse what cannot be opened as a file with a message saying why.
void require_readable_file(const std::string& path) {
    std::error_code ec;
    fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) throw ExrError(path, "cannot open: no such file");
    if (fs::is_directory(st)) throw ExrError(path, "cannot open: is a directory");
    if (!fs::is_regular_file(st)) throw ExrError(path, "cannot open: not a regular file");
}

std::vector<char> load_file(const std::string& path) {
    require_readable_file(path);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ExrError(path, "cannot open: " + errno_text(errno));
    in.seekg(0, std::ios::end);
    std::streamoff size = in.tellg();
    in.seekg(0, std::ios::beg);
    if (size < 0) throw ExrError(path, "cannot read: " + errno_text(errno));
    std::vector<char> data(static_cast<std::size_t>(size));
    if (size > 0 && !in.read(data.data(), size)) throw ExrError(path, "cannot read: " + errno_text(errno));
    return data;
}

// An Imf::IStream over bytes already in memory, so the bytes that
// checkOpenEXRFile approved are exactly the bytes decoded.
class MemoryIStream : public Imf::IStream {
public:
    MemoryIStream(const std::vector<char>& data, const std::string& name) : Imf::IStream(name.c_str()), data_(data) {}
    bool read(char c[], int n) override {
        if (n < 0 || pos_ > data_.size() || static_cast<std::size_t>(n) > data_.size() - pos_)
            throw IEX_NAMESPACE::InputExc("Unexpected end of file.");
        std::memcpy(c, data_.data() + pos_, static_cast<std::size_t>(n));
        pos_ += std::size_t(n);
        return pos_ < data_.size();
    }
    uint64_t tellg() override { return pos_; }
    void seekg(uint64_t pos) override { pos_ = static_cast<std::size_t>(pos); }

private:
    const std::vector<char>& data_;
    std::size_t pos_ = 0;
};

bool same_window(const Imath::Box2i& a, const Imath::Box2i& b) { return a.min == b.min && a.max == b.max; }

void check_window(const std::string& path, std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1) {
    if (x1 < x0 || y1 < y0) throw ExrError(path, "empty data window");
    std::int64_t w = x1 - x0 + 1, h = y1 - y0 + 1;
    if (w > std::numeric_limits<int>::max() || h > std::numeric_limits<int>::max() || w * h > kMaxPixels)
        throw ExrError(path, "data window " + std::to_string(w) + "x" + std::to_string(h) + " is too large");
}

Imf::Compression to_imf(Compression c) {
    switch (c) {
        case Compression::None: return Imf::NO_COMPRESSION;
        case Compression::Zip: return Imf::ZIP_COMPRESSION;
        case Compression::Zips: return Imf::ZIPS_COMPRESSION;
        case Compression::Piz: return Imf::PIZ_COMPRESSION;
        case Compression::Rle: return Imf::RLE_COMPRESSION;
    }
    return Imf::ZIP_COMPRESSION;
}

// The Core library reports errors through a callback; keep the last text.
thread_local std::string t_core_message;
void core_error_handler(exr_const_context_t, exr_result_t, const char* msg) { t_core_message = msg ? msg : ""; }

std::string temporary_name_for(const fs::path& target) {
    static thread_local std::mt19937_64 rng{std::random_device{}() ^ static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(&rng))};
    const char* hex = "0123456789abcdef";
    std::string suffix;
    std::uint64_t r = rng();
    for (int i = 0; i < 12; ++i, r >>= 4) suffix += hex[r & 15];
    fs::path dir = target.parent_path();
    return (dir / ("." + target.filename().string() + ".tmp-" + suffix)).string();
}

// OpenEXR 3.1's C++ reader (checkOpenEXRFile's included) allocates what a
// header attribute declares before reading it (an opaque attribute's size, a
// stringvector element's length): a few bytes can make it allocate 2 GB.
// And it reads typed attributes by their type, not their declared size, so a
// wrong size desynchronises the header.  Before OpenEXR sees the bytes, walk
// the attribute table (name\0 type\0 int32 size, value; a header ends with an
// empty name; a multi-part file's list of headers ends with an empty header)
// and refuse anything whose value does not fit in the file, whose size is not
// the one its type implies, or whose inner lengths overrun the value.
std::size_t fixed_attribute_size(const std::string& type) {
    static const std::map<std::string, std::size_t> sizes = {
        {"box2i", 16},   {"box2f", 16},      {"v2i", 8},       {"v2f", 8},      {"v2d", 16},
        {"v3i", 12},     {"v3f", 12},        {"v3d", 24},      {"int", 4},      {"float", 4},
        {"double", 8},   {"compression", 1}, {"lineOrder", 1}, {"envmap", 1},   {"deepImageState", 1},
        {"tiledesc", 9}, {"rational", 8},    {"timecode", 8},  {"keycode", 28}, {"chromaticities", 32},
        {"m33f", 36},    {"m33d", 72},       {"m44f", 64},     {"m44d", 128}};
    auto it = sizes.find(type);
    return it == sizes.end() ? 0 : it->second;
}

void check_attribute_sizes(const std::string& path, const std::vector<char>& data) {
    const std::size_t n = data.size();
    std::size_t pos = 8;  // magic number, version and flags
    if (n < pos) throw ExrError(path, "truncated before the header");
    const bool multipart = (static_cast<unsigned char>(data[5]) & 0x10) != 0;  // flag 0x1000
    auto bad = [&](const std::string& what) { throw ExrError(path, "corrupt header: " + what); };
    auto string_at = [&](std::size_t& at, std::size_t end, const char* what) {
        std::size_t start = at;
        while (at < end && data[at] != 0 && at - start < 255) ++at;
        if (at >= end || data[at] != 0) bad(std::string("unterminated ") + what);
        return std::string(data.data() + start, (at++) - start);
    };
    auto int_at = [&](std::size_t at) {
        std::uint32_t v = 0;
        for (int b = 3; b >= 0; --b) v = (v << 8) | static_cast<unsigned char>(data[at + b]);
        return v;
    };
    for (int part = 0;; ++part) {
        if (part > 0 && (!multipart || (pos < n && data[pos] == 0)))
            return;  // single part, or the empty header that ends a multi-part list
        for (;;) {
            const std::string name = string_at(pos, n, "attribute name");
            if (name.empty()) break;
            const std::string type = string_at(pos, n, "attribute type");
            if (n - pos < 4) bad("attribute '" + name + "' has no size");
            const std::uint32_t size = int_at(pos);
            pos += 4;
            if (size > n - pos)
                bad("attribute '" + name + "' claims " + std::to_string(size) + " bytes, the file has " + std::to_string(n - pos) +
                    " left");
            const std::size_t end = pos + size;
            const std::size_t fixed = fixed_attribute_size(type);
            if (fixed && size != fixed) bad("attribute '" + name + "' of type " + type + " has size " + std::to_string(size));
            if (type == "chlist") {  // entries: name\0 + 16 bytes; an empty name ends the list
                std::size_t at = pos;
                while (at < end && data[at] != 0) {
                    string_at(at, end, "channel name");
                    at += 16;
                }
                if (at + 1 != end) bad("channel list of '" + name + "' does not end at its size");
            } else if (type == "preview") {  // width, height, 4 bytes a pixel
                if (size < 8 || std::uint64_t(int_at(pos)) * int_at(pos + 4) * 4 != size - 8)
                    bad("preview image of '" + name + "' does not match its size");
            } else if (type == "stringvector") {  // int32 length + bytes, repeated
                for (std::size_t at = pos; at < end;) {
                    if (end - at < 4 || int_at(at) > end - at - 4) bad("string vector '" + name + "' overruns its size");
                    at += 4 + int_at(at);
                }
            }
            pos = end;
        }
    }
}

}  // namespace

ExrImage read_exr(const std::string& path) {
    std::vector<char> data = load_file(path);
    if (data.size() < 4 || !Imf::isImfMagic(data.data())) throw ExrError(path, "not an OpenEXR file (bad magic number)");
    check_attribute_sizes(path, data);
    // Returns true when the file is NOT valid.  The Core library's checks are
    // left out: OpenEXR 3.1 decodes through the C++ library, checked here.
    if (Imf::checkOpenEXRFile(data.data(), data.size(), /*reduceMemory*/ true,
                              /*reduceTime*/ true, /*enableCoreCheck*/ false))
        throw ExrError(path, "corrupt or truncated OpenEXR file (OpenEXR's checkOpenEXRFile refused it)");

    ExrImage image;
    try {
        MemoryIStream stream(data, path);
        Imf::MultiPartInputFile file(stream);
        // Bytes decoding would allocate: 4 per sample of the image, plus
        // OpenEXR's chunk buffers (up to 256 scanlines, DWAB's, or a tile).
        std::uint64_t decoded = 0;
        for (int p = 0; p < file.parts(); ++p) {
            const Imf::Header& header = file.header(p);
            const Imath::Box2i& dw = header.dataWindow();
            check_window(path, dw.min.x, dw.min.y, dw.max.x, dw.max.y);
            std::uint64_t channels = 0;
            for (auto c = header.channels().begin(); c != header.channels().end(); ++c) ++channels;
            const std::uint64_t w = std::uint64_t(std::int64_t(dw.max.x) - dw.min.x + 1);
            const std::uint64_t h = std::uint64_t(std::int64_t(dw.max.y) - dw.min.y + 1);
            std::uint64_t chunk = w * 256;
            if (header.hasTileDescription()) chunk = std::uint64_t(header.tileDescription().xSize) * header.tileDescription().ySize;
            decoded += channels * 4 * (w * h + chunk);
        }
        if (decoded > std::max(kMinDecodeBudget, kMaxCompressionRatio * data.size()))
            throw ExrError(path, "the header promises " + std::to_string(decoded) + " bytes of pixels in a " + std::to_string(data.size()) +
                                     "-byte file: refused as corrupt");
        Imath::Box2i window;
        for (int p = 0; p < file.parts(); ++p) {
            const Imf::Header& header = file.header(p);
            if (header.hasType() && Imf::isDeepData(header.type()))
                throw ExrError(path, "part " + std::to_string(p) + " holds deep data, which is not supported");
            const Imath::Box2i& dw = header.dataWindow();
            if (p == 0) {
                check_window(path, dw.min.x, dw.min.y, dw.max.x, dw.max.y);
                window = dw;
                image.width = dw.max.x - dw.min.x + 1;
                image.height = dw.max.y - dw.min.y + 1;
                for (auto it = header.begin(); it != header.end(); ++it) {
                    std::string name = it.name();
                    if (name == "name" || name == "type") continue;
                    if (auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) image.attributes[name] = s->value();
                }
            } else if (!same_window(dw, window)) {
                throw ExrError(path, "part " + std::to_string(p) + " has a data window different from part 0's");
            }
            const std::size_t n = image.pixel_count();
            Imf::FrameBuffer fb;
            for (auto c = header.channels().begin(); c != header.channels().end(); ++c) {
                const std::string name = c.name();
                const Imf::Channel& ch = c.channel();
                if (ch.xSampling != 1 || ch.ySampling != 1)
                    throw ExrError(path, "channel '" + name + "' is subsampled, which is not supported");
                if (image.has(name)) throw ExrError(path, "channel '" + name + "' appears in more than one part");
                if (ch.type == Imf::UINT) {
                    auto& v = image.uint_channels[name];
                    v.assign(n, 0u);
                    fb.insert(name, Imf::Slice::Make(Imf::UINT, v.data(), dw, sizeof(uint32_t)));
                } else {
                    auto& v = image.channels[name];
                    v.assign(n, 0.0f);
                    fb.insert(name, Imf::Slice::Make(Imf::FLOAT, v.data(), dw, sizeof(float)));
                }
            }
            Imf::InputPart part(file, p);
            part.setFrameBuffer(fb);
            part.readPixels(dw.min.y, dw.max.y);
        }
    } catch (const ExrError&) {
        throw;
    } catch (const std::exception& e) {
        throw ExrError(path, std::string("cannot decode: ") + e.what());
    }
    return image;
}

ExrInfo read_exr_info(const std::string& path) {
    require_readable_file(path);
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = &core_error_handler;
    exr_context_t ctx = nullptr;
    t_core_message.clear();
    exr_result_t rv = exr_start_read(&ctx, path.c_str(), &init);
    auto fail = [&](exr_result_t code) {
        std::string msg = t_core_message.empty() ? exr_get_default_error_message(code) : t_core_message;
        if (ctx) exr_finish(&ctx);
        throw ExrError(path, "not a readable OpenEXR file: " + msg);
    };
    if (rv != EXR_ERR_SUCCESS) fail(rv);

    ExrInfo info;
    int parts = 0;
    if ((rv = exr_get_count(ctx, &parts)) != EXR_ERR_SUCCESS) fail(rv);
    info.parts = parts;
    exr_attr_box2i_t window{};
    for (int p = 0; p < parts; ++p) {
        exr_storage_t storage;
        exr_attr_box2i_t dw;
        const exr_attr_chlist_t* chlist = nullptr;
        if ((rv = exr_get_storage(ctx, p, &storage)) != EXR_ERR_SUCCESS || (rv = exr_get_data_window(ctx, p, &dw)) != EXR_ERR_SUCCESS ||
            (rv = exr_get_channels(ctx, p, &chlist)) != EXR_ERR_SUCCESS)
            fail(rv);
        try {
            if (storage == EXR_STORAGE_DEEP_SCANLINE || storage == EXR_STORAGE_DEEP_TILED)
                throw ExrError(path, "part " + std::to_string(p) + " holds deep data, which is not supported");
            if (p == 0) {
                check_window(path, dw.min.x, dw.min.y, dw.max.x, dw.max.y);
                window = dw;
                info.width = dw.max.x - dw.min.x + 1;
                info.height = dw.max.y - dw.min.y + 1;
            } else if (dw.min.x != window.min.x || dw.min.y != window.min.y || dw.max.x != window.max.x || dw.max.y != window.max.y) {
                throw ExrError(path, "part " + std::to_string(p) + " has a data window different from part 0's");
            }
        } catch (...) {
            exr_finish(&ctx);
            throw;
        }
        for (int c = 0; chlist && c < chlist->num_channels; ++c) {
            const exr_attr_chlist_entry_t& e = chlist->entries[c];
            ExrChannelInfo ci;
            ci.name.assign(e.name.str, static_cast<std::size_t>(std::max(0, e.name.length)));
            ci.type = e.pixel_type == EXR_PIXEL_UINT   ? PixelType::Uint
                      : e.pixel_type == EXR_PIXEL_HALF ? PixelType::Half
                                                       : PixelType::Float;
            ci.part = p;
            info.channels.push_back(std::move(ci));
        }
    }
    exr_finish(&ctx);
    std::sort(info.channels.begin(), info.channels.end(), [](const ExrChannelInfo& a, const ExrChannelInfo& b) { return a.name < b.name; });
    return info;
}

void verify_exr_chunks(const std::string& path) {
    require_readable_file(path);
    std::error_code size_ec;
    const std::uintmax_t file_size = fs::file_size(path, size_ec);
    if (size_ec) throw ExrError(path, "cannot read: " + size_ec.message());
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = &core_error_handler;
    exr_context_t ctx = nullptr;
    t_core_message.clear();
    auto fail = [&](exr_result_t code, const std::string& what) {
        std::string msg = t_core_message.empty() ? exr_get_default_error_message(code) : t_core_message;
        if (ctx) exr_finish(&ctx);
        throw ExrError(path, "truncated or corrupt OpenEXR file: " + what + ": " + msg);
    };
    exr_result_t rv = exr_start_read(&ctx, path.c_str(), &init);
    if (rv != EXR_ERR_SUCCESS) {
        std::string msg = t_core_message.empty() ? exr_get_default_error_message(rv) : t_core_message;
        if (ctx) exr_finish(&ctx);
        throw ExrError(path, "not a readable OpenEXR file: " + msg);
    }
    int parts = 0;
    if ((rv = exr_get_count(ctx, &parts)) != EXR_ERR_SUCCESS) fail(rv, "part count");
    auto check_block = [&](const exr_chunk_info_t& ci, const std::string& where) {
        if (ci.data_offset > file_size || ci.packed_size > file_size - ci.data_offset) {
            exr_finish(&ctx);
            throw ExrError(path, "truncated OpenEXR file: " + where + " ends at byte " + std::to_string(ci.data_offset + ci.packed_size) +
                                     " but the file has " + std::to_string(file_size) + " bytes");
        }
    };
    for (int p = 0; p < parts; ++p) {
        exr_storage_t storage;
        exr_attr_box2i_t dw;
        if ((rv = exr_get_storage(ctx, p, &storage)) != EXR_ERR_SUCCESS || (rv = exr_get_data_window(ctx, p, &dw)) != EXR_ERR_SUCCESS)
            fail(rv, "part " + std::to_string(p));
        const std::string part = parts > 1 ? "part " + std::to_string(p) + ", " : "";
        if (storage == EXR_STORAGE_SCANLINE || storage == EXR_STORAGE_DEEP_SCANLINE) {
            int32_t lines = 0;
            if ((rv = exr_get_scanlines_per_chunk(ctx, p, &lines)) != EXR_ERR_SUCCESS || lines <= 0)
                fail(rv == EXR_ERR_SUCCESS ? EXR_ERR_INVALID_ATTR : rv, part + "scanlines per block");
            for (int64_t y = dw.min.y; y <= dw.max.y; y += lines) {
                exr_chunk_info_t ci;
                const std::string where = part + "the block of scanline " + std::to_string(y);
                if ((rv = exr_read_scanline_chunk_info(ctx, p, static_cast<int>(y), &ci)) != EXR_ERR_SUCCESS) fail(rv, where);
                check_block(ci, where);
            }
        } else {
            uint32_t tw = 0, th = 0;
            exr_tile_level_mode_t level_mode;
            exr_tile_round_mode_t round_mode;
            int32_t levels_x = 0, levels_y = 0;
            if ((rv = exr_get_tile_descriptor(ctx, p, &tw, &th, &level_mode, &round_mode)) != EXR_ERR_SUCCESS ||
                (rv = exr_get_tile_levels(ctx, p, &levels_x, &levels_y)) != EXR_ERR_SUCCESS)
                fail(rv, part + "tile description");
            for (int ly = 0; ly < levels_y; ++ly)
                for (int lx = 0; lx < levels_x; ++lx) {
                    if (level_mode != EXR_TILE_RIPMAP_LEVELS && lx != ly) continue;
                    int32_t lw = 0, lh = 0, sw = 0, sh = 0;
                    if ((rv = exr_get_level_sizes(ctx, p, lx, ly, &lw, &lh)) != EXR_ERR_SUCCESS ||
                        (rv = exr_get_tile_sizes(ctx, p, lx, ly, &sw, &sh)) != EXR_ERR_SUCCESS || sw <= 0 || sh <= 0)
                        fail(rv == EXR_ERR_SUCCESS ? EXR_ERR_INVALID_ATTR : rv, part + "tile level sizes");
                    for (int ty = 0; ty < (lh + sh - 1) / sh; ++ty)
                        for (int tx = 0; tx < (lw + sw - 1) / sw; ++tx) {
                            exr_chunk_info_t ci;
                            const std::string where = part + "tile (" + std::to_string(tx) + ", " + std::to_string(ty) + ") of level (" +
                                                      std::to_string(lx) + ", " + std::to_string(ly) + ")";
                            if ((rv = exr_read_tile_chunk_info(ctx, p, tx, ty, lx, ly, &ci)) != EXR_ERR_SUCCESS) fail(rv, where);
                            check_block(ci, where);
                        }
                }
        }
    }
    exr_finish(&ctx);
}

void set_thread_count(int threads) { Imf::setGlobalThreadCount(threads > 0 ? threads : 0); }

std::vector<std::string> channel_names(const std::string& path) {
    std::vector<std::string> names;
    for (const ExrChannelInfo& c : read_exr_info(path).channels) names.push_back(c.name);
    return names;
}

std::vector<std::string> channel_names(const ExrImage& image) {
    std::vector<std::string> names;
    for (const auto& kv : image.channels) names.push_back(kv.first);
    for (const auto& kv : image.uint_channels) names.push_back(kv.first);
    std::sort(names.begin(), names.end());
    return names;
}

void write_exr(const std::string& path, const ExrImage& image, const WriteOptions& options) {
    if (image.width <= 0 || image.height <= 0)
        throw ExrError(path, "cannot write an image of size " + std::to_string(image.width) + "x" + std::to_string(image.height));
    if (image.channels.empty() && image.uint_channels.empty()) throw ExrError(path, "cannot write an image without channels");
    const std::size_t n = image.pixel_count();
    auto check_channel = [&](const std::string& name, std::size_t size) {
        if (name.empty()) throw ExrError(path, "cannot write a channel with an empty name");
        if (size != n)
            throw ExrError(path, "channel '" + name + "' holds " + std::to_string(size) + " values, expected " + std::to_string(n) + " (" +
                                     std::to_string(image.width) + "x" + std::to_string(image.height) + ")");
    };
    for (const auto& kv : image.channels) check_channel(kv.first, kv.second.size());
    for (const auto& kv : image.uint_channels) {
        check_channel(kv.first, kv.second.size());
        if (image.channels.count(kv.first)) throw ExrError(path, "channel '" + kv.first + "' is both a float and a UINT channel");
    }

    const fs::path target(path);
    if (target.filename().empty()) throw ExrError(path, "not a file name");
    std::error_code ec;
    if (fs::is_directory(target, ec)) throw ExrError(path, "cannot write: is a directory");
    const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    if (!fs::is_directory(dir, ec)) throw ExrError(path, "cannot write: directory '" + dir.string() + "' does not exist");

    const std::string tmp = temporary_name_for(target);
    try {
        const std::set<std::string> as_half(options.half_channels.begin(), options.half_channels.end());
        // Channels grouped into parts: one part, or one per layer.
        std::map<std::string, std::vector<std::string>> parts;
        auto part_of = [&](const std::string& name) {
            if (!options.multipart_by_layer) return std::string();
            const std::size_t dot = name.rfind('.');
            return dot == std::string::npos ? std::string() : name.substr(0, dot);
        };
        for (const auto& kv : image.channels) parts[part_of(kv.first)].push_back(kv.first);
        for (const auto& kv : image.uint_channels) parts[part_of(kv.first)].push_back(kv.first);

        std::vector<Imf::Header> headers;
        std::vector<Imf::FrameBuffer> buffers;
        // OpenEXR writes each channel from a slice of its own type: HALF
        // channels get a rounded copy (Imath's half(float) rounds to nearest even).
        std::map<std::string, std::vector<half>> half_copies;
        const std::size_t hxs = sizeof(half), hys = sizeof(half) * static_cast<std::size_t>(image.width);
        const std::size_t xs = sizeof(float), ys = sizeof(float) * static_cast<std::size_t>(image.width);
        for (const auto& part : parts) {
            Imf::Header header(image.width, image.height);
            header.compression() = to_imf(options.compression);
            if (headers.empty())
                for (const auto& kv : image.attributes) header.insert(kv.first, Imf::StringAttribute(kv.second));
            if (options.multipart_by_layer) {
                header.setName(part.first.empty() ? "default" : part.first);
                header.setType(Imf::SCANLINEIMAGE);
            }
            Imf::FrameBuffer fb;
            for (const std::string& name : part.second) {
                if (auto it = image.channels.find(name); it != image.channels.end() && as_half.count(name)) {
                    std::vector<half>& h = half_copies[name];
                    h.assign(it->second.begin(), it->second.end());
                    header.channels().insert(name, Imf::Channel(Imf::HALF));
                    fb.insert(name, Imf::Slice(Imf::HALF, reinterpret_cast<char*>(h.data()), hxs, hys));
                } else if (it != image.channels.end()) {
                    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
                    char* base = reinterpret_cast<char*>(const_cast<float*>(it->second.data()));
                    fb.insert(name, Imf::Slice(Imf::FLOAT, base, xs, ys));
                } else {
                    const auto& v = image.uint_channels.at(name);
                    header.channels().insert(name, Imf::Channel(Imf::UINT));
                    char* base = reinterpret_cast<char*>(const_cast<uint32_t*>(v.data()));
                    fb.insert(name, Imf::Slice(Imf::UINT, base, xs, ys));
                }
            }
            headers.push_back(header);
            buffers.push_back(fb);
        }

        std::ofstream os(tmp, std::ios::binary | std::ios::trunc);
        if (!os) throw ExrError(path, "cannot create '" + tmp + "': " + errno_text(errno));
        {
            Imf::StdOFStream stream(os, tmp.c_str());
            if (!options.multipart_by_layer) {
                Imf::OutputFile file(stream, headers[0]);
                file.setFrameBuffer(buffers[0]);
                file.writePixels(image.height);
            } else {
                Imf::MultiPartOutputFile file(stream, headers.data(), static_cast<int>(headers.size()));
                for (int p = 0; p < static_cast<int>(headers.size()); ++p) {
                    Imf::OutputPart part(file, p);
                    part.setFrameBuffer(buffers[static_cast<std::size_t>(p)]);
                    part.writePixels(image.height);
                }
            }
        }  // the destructor writes the offset table; a failure there shows on `os`
        os.flush();
        os.close();
        if (!os) throw ExrError(path, "cannot write '" + tmp + "': " + errno_text(errno));
        fs::rename(tmp, target);
    } catch (const std::exception& e) {
        fs::remove(tmp, ec);
        if (dynamic_cast<const ExrError*>(&e)) throw;
        throw ExrError(path, std::string("cannot write: ") + e.what());
    }
}

}  // namespace rrc_exr
