// Writes the EXR seed corpus of rrc_fuzz_exr (corpus/exr/): tiny files of
// the kinds rrc-accumulate reads (depth, previous clip, motion, signal
// layers, UINT ids, string attributes) in every compression it writes.
// Small on purpose: libFuzzer mutates bytes, and 4x3 images keep inputs short.
//   rrc_make_exr_seeds <directory>
#include "exr_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>

#include <cstdio>
#include <string>
#include <vector>

// Two scanline parts sharing a data window (as multi-layer renderers write),
// through OpenEXR directly: rrc_exr writes single-part files only.
static void write_two_parts(const std::string& path) {
    std::vector<Imf::Header> headers;
    for (const char* part : {"beauty", "aux"}) {
        Imf::Header h(2, 2);
        h.setName(part);
        h.setType(Imf::SCANLINEIMAGE);
        h.compression() = Imf::NO_COMPRESSION;
        h.channels().insert(std::string(part) + ".Y", Imf::Channel(Imf::FLOAT));
        headers.push_back(h);
    }
    Imf::MultiPartOutputFile file(path.c_str(), headers.data(), (int)headers.size());
    std::vector<float> values = {0.25f, 0.5f, 0.75f, 1.0f};
    for (int p = 0; p < 2; ++p) {
        Imf::OutputPart part(file, p);
        Imf::FrameBuffer fb;
        fb.insert(std::string(p == 0 ? "beauty" : "aux") + ".Y",
                  Imf::Slice(Imf::FLOAT, (char*)values.data(), sizeof(float), 2 * sizeof(float)));
        part.setFrameBuffer(fb);
        part.writePixels(2);
    }
}

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s <directory>\n", argv[0]);
        return 2;
    }
    const std::string dir = argv[1];
    rrc_exr::ExrImage image;
    image.width = 4;
    image.height = 3;
    const size_t n = 12;
    for (const char* name : {"Z", "prevclip.X", "prevclip.Y", "prevclip.Z", "prevclip.W", "mv.X", "mv.Y", "shadow.Y", "color.R"}) {
        std::vector<float> v(n);
        for (size_t i = 0; i < n; ++i) v[i] = 0.25f * (float)i - 1.0f;
        image.channels[name] = v;
    }
    image.uint_channels["rrc.mask"] = std::vector<uint32_t>(n, 5u);
    image.attributes["rrc.note"] = "seed";
    const struct {
        rrc_exr::Compression c;
        const char* name;
    } kinds[] = {{rrc_exr::Compression::None, "none"},
                 {rrc_exr::Compression::Zip, "zip"},
                 {rrc_exr::Compression::Zips, "zips"},
                 {rrc_exr::Compression::Piz, "piz"},
                 {rrc_exr::Compression::Rle, "rle"}};
    for (const auto& k : kinds) {
        rrc_exr::WriteOptions options;
        options.compression = k.c;
        rrc_exr::write_exr(dir + "/seed_" + k.name + ".exr", image, options);
    }
    rrc_exr::ExrImage minimal;  // one pixel, one channel
    minimal.width = minimal.height = 1;
    minimal.channels["Z"] = {0.5f};
    rrc_exr::WriteOptions none;
    none.compression = rrc_exr::Compression::None;
    rrc_exr::write_exr(dir + "/seed_minimal.exr", minimal, none);
    write_two_parts(dir + "/seed_two_parts.exr");
    return 0;
}
