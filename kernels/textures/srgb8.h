/* The linear value of each 8-bit sRGB code, looked up instead of computed.
 *
 * wp_srgb8_to_linear[k] is wp_srgb_to_linear(k / 255) (bitmap.h) as PoCL 3.1
 * computes it on this project's CPU device, the float from the kernel's own
 * formula, so a texture decoded by the table renders bit for bit as one
 * decoded by the formula did: a lookup instead of a pow (about a tenth of
 * the showcase's shade time went to the pow, docs/performance.md, "The
 * showcase's shade, profiled and cut"). The values lie within 5 ulps of the
 * correctly rounded curve; tests/kernels/test_textures.cpp checks both, the
 * device formula entry by entry and the double-precision curve.
 */
#ifndef WP_TEXTURES_SRGB8_H
#define WP_TEXTURES_SRGB8_H

__constant float wp_srgb8_to_linear[256] = {
    0x0p+0f,         0x1.3e4568p-12f, 0x1.3e4568p-11f, 0x1.dd681ep-11f, 0x1.3e4568p-10f,
    0x1.8dd6c2p-10f, 0x1.dd681ep-10f, 0x1.167cbcp-9f,  0x1.3e4568p-9f,  0x1.660e16p-9f,
    0x1.8dd6c2p-9f,  0x1.b6a31ap-9f,  0x1.e1e31ap-9f,  0x1.07c38cp-8f,  0x1.1fcc2cp-8f,
    0x1.390ffap-8f,  0x1.53936ap-8f,  0x1.6f5adcp-8f,  0x1.8c6a92p-8f,  0x1.aac6bep-8f,
    0x1.ca7382p-8f,  0x1.eb74ep-8f,   0x1.06e76ap-7f,  0x1.18c2a4p-7f,  0x1.2b4e06p-7f,
    0x1.3e8b7cp-7f,  0x1.527cd6p-7f,  0x1.6723eep-7f,  0x1.7c829p-7f,   0x1.929a86p-7f,
    0x1.a96d8ep-7f,  0x1.c0fd62p-7f,  0x1.d94bb8p-7f,  0x1.f25a44p-7f,  0x1.06155p-6f,
    0x1.135f3cp-6f,  0x1.210bb6p-6f,  0x1.2f1b8ap-6f,  0x1.3d8f8p-6f,   0x1.4c6864p-6f,
    0x1.5ba6fap-6f,  0x1.6b4c02p-6f,  0x1.7b584p-6f,   0x1.8bcc72p-6f,  0x1.9ca956p-6f,
    0x1.adefa6p-6f,  0x1.bfa01cp-6f,  0x1.d1bb72p-6f,  0x1.e44262p-6f,  0x1.f7358cp-6f,
    0x1.054ad8p-5f,  0x1.0f31bep-5f,  0x1.194fcep-5f,  0x1.23a56p-5f,   0x1.2e32cap-5f,
    0x1.38f862p-5f,  0x1.43f678p-5f,  0x1.4f2d64p-5f,  0x1.5a9d7cp-5f,  0x1.664708p-5f,
    0x1.722a5cp-5f,  0x1.7e47ccp-5f,  0x1.8a9fa8p-5f,  0x1.97323ep-5f,  0x1.a3ffdcp-5f,
    0x1.b108d4p-5f,  0x1.be4d7p-5f,   0x1.cbcdfcp-5f,  0x1.d98ac8p-5f,  0x1.e7841ep-5f,
    0x1.f5ba4ap-5f,  0x1.0216ccp-4f,  0x1.096f2ap-4f,  0x1.10e66p-4f,   0x1.187c94p-4f,
    0x1.2031ecp-4f,  0x1.28068ap-4f,  0x1.2ffa94p-4f,  0x1.380e2cp-4f,  0x1.404176p-4f,
    0x1.489496p-4f,  0x1.5107aep-4f,  0x1.599aep-4f,   0x1.624e5p-4f,   0x1.6b222p-4f,
    0x1.74167p-4f,   0x1.7d2b6ap-4f,  0x1.866124p-4f,  0x1.8fb7c4p-4f,  0x1.992f6cp-4f,
    0x1.a2c83ep-4f,  0x1.ac8258p-4f,  0x1.b65ddep-4f,  0x1.c05aeep-4f,  0x1.ca79aap-4f,
    0x1.d4ba32p-4f,  0x1.df1caap-4f,  0x1.e9a126p-4f,  0x1.f447dp-4f,   0x1.ff10c2p-4f,
    0x1.04fe0ep-3f,  0x1.0a8504p-3f,  0x1.101d4ap-3f,  0x1.15c6f2p-3f,  0x1.1b820ep-3f,
    0x1.214eaap-3f,  0x1.272cd8p-3f,  0x1.2d1ca6p-3f,  0x1.331e22p-3f,  0x1.39315cp-3f,
    0x1.3f5664p-3f,  0x1.458d46p-3f,  0x1.4bd612p-3f,  0x1.5230d8p-3f,  0x1.589da4p-3f,
    0x1.5f1c8ap-3f,  0x1.65ad9p-3f,   0x1.6c50c8p-3f,  0x1.730644p-3f,  0x1.79ce0cp-3f,
    0x1.80a832p-3f,  0x1.8794c4p-3f,  0x1.8e93dp-3f,   0x1.95a564p-3f,  0x1.9cc98cp-3f,
    0x1.a40056p-3f,  0x1.ab49d4p-3f,  0x1.b2a60ep-3f,  0x1.ba1516p-3f,  0x1.c196f8p-3f,
    0x1.c92bcp-3f,   0x1.d0d37ep-3f,  0x1.d88e4p-3f,   0x1.e05c1p-3f,   0x1.e83cfep-3f,
    0x1.f03118p-3f,  0x1.f8387p-3f,   0x1.002984p-2f,  0x1.044078p-2f,  0x1.08611ap-2f,
    0x1.0c8b74p-2f,  0x1.10bf8ap-2f,  0x1.14fd64p-2f,  0x1.194506p-2f,  0x1.1d967ap-2f,
    0x1.21f1c2p-2f,  0x1.2656e8p-2f,  0x1.2ac5fp-2f,   0x1.2f3ee2p-2f,  0x1.33c1c4p-2f,
    0x1.384e9cp-2f,  0x1.3ce57p-2f,   0x1.418644p-2f,  0x1.463124p-2f,  0x1.4ae61p-2f,
    0x1.4fa512p-2f,  0x1.546e3p-2f,   0x1.59416ep-2f,  0x1.5e1ed2p-2f,  0x1.630666p-2f,
    0x1.67f82cp-2f,  0x1.6cf42ap-2f,  0x1.71fa68p-2f,  0x1.770aecp-2f,  0x1.7c25cp-2f,
    0x1.814ae2p-2f,  0x1.867a5ap-2f,  0x1.8bb42ep-2f,  0x1.90f866p-2f,  0x1.964706p-2f,
    0x1.9ba016p-2f,  0x1.a1039ap-2f,  0x1.a67198p-2f,  0x1.abea16p-2f,  0x1.b16d1ap-2f,
    0x1.b6faa8p-2f,  0x1.bc92cap-2f,  0x1.c23582p-2f,  0x1.c7e2d6p-2f,  0x1.cd9acep-2f,
    0x1.d35d6cp-2f,  0x1.d92abap-2f,  0x1.df02bap-2f,  0x1.e4e574p-2f,  0x1.ead2ecp-2f,
    0x1.f0cb28p-2f,  0x1.f6ce2ep-2f,  0x1.fcdc04p-2f,  0x1.017a56p-1f,  0x1.048c18p-1f,
    0x1.07a34ap-1f,  0x1.0abffp-1f,   0x1.0de20cp-1f,  0x1.11099ep-1f,  0x1.1436aep-1f,
    0x1.17693ap-1f,  0x1.1aa144p-1f,  0x1.1dded2p-1f,  0x1.2121e4p-1f,  0x1.246a8p-1f,
    0x1.27b8a6p-1f,  0x1.2b0c5ap-1f,  0x1.2e659ep-1f,  0x1.31c476p-1f,  0x1.3528e2p-1f,
    0x1.3892e6p-1f,  0x1.3c0286p-1f,  0x1.3f77c2p-1f,  0x1.42f2ap-1f,   0x1.46732p-1f,
    0x1.49f944p-1f,  0x1.4d851p-1f,   0x1.511686p-1f,  0x1.54adaap-1f,  0x1.584a7ep-1f,
    0x1.5bed04p-1f,  0x1.5f953cp-1f,  0x1.63432ep-1f,  0x1.66f6d8p-1f,  0x1.6ab04p-1f,
    0x1.6e6f66p-1f,  0x1.72344cp-1f,  0x1.75fefcp-1f,  0x1.79cf6cp-1f,  0x1.7da5a8p-1f,
    0x1.8181acp-1f,  0x1.85638p-1f,   0x1.894b24p-1f,  0x1.8d389ap-1f,  0x1.912be6p-1f,
    0x1.952508p-1f,  0x1.992406p-1f,  0x1.9d28ep-1f,   0x1.a1339ap-1f,  0x1.a54434p-1f,
    0x1.a95ab2p-1f,  0x1.ad7718p-1f,  0x1.b19966p-1f,  0x1.b5c19ep-1f,  0x1.b9efc4p-1f,
    0x1.be23dcp-1f,  0x1.c25de4p-1f,  0x1.c69ddep-1f,  0x1.cae3d8p-1f,  0x1.cf2fc2p-1f,
    0x1.d381bp-1f,   0x1.d7d996p-1f,  0x1.dc3784p-1f,  0x1.e09b6cp-1f,  0x1.e50562p-1f,
    0x1.e9755cp-1f,  0x1.edeb66p-1f,  0x1.f2677p-1f,   0x1.f6e996p-1f,  0x1.fb71cp-1f,
    0x1p+0f,
};

#endif /* WP_TEXTURES_SRGB8_H */
