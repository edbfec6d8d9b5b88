// ContactTracks: a slot's contact is held from its begin to its end, and the records of
// ended contacts are handed to later ones.
#include <gtest/gtest.h>

#include "contacts/contact_tracks.h"

namespace cyclone::test {
namespace {

using detail::ContactTrack;
using detail::ContactTracks;

ContactTrack touching(std::uint32_t a, std::uint32_t b, std::uint64_t userData) {
    ContactTrack t;
    t.a.index = a;
    t.b.index = b;
    t.touching = true;
    t.userDataA = userData;
    t.userDataB = userData + 1;
    return t;
}

TEST(ContactTracks, HoldsEachSlotsContactFromBeginToEnd) {
    ContactTracks tracks;
    tracks.cover(10);
    EXPECT_EQ(tracks.slots(), 10u);
    for (std::uint32_t slot = 0; slot < 12; ++slot) EXPECT_FALSE(tracks.at(slot).touching) << slot;
    tracks.begin(3, touching(1, 2, 7));
    tracks.begin(8, touching(4, 5, 9));
    EXPECT_TRUE(tracks.at(3).touching);
    EXPECT_EQ(tracks.at(3).a.index, 1u);
    EXPECT_EQ(tracks.at(3).userDataB, 8u);
    EXPECT_EQ(tracks.at(8).b.index, 5u);
    EXPECT_FALSE(tracks.at(4).touching);
    tracks.end(3);
    EXPECT_FALSE(tracks.at(3).touching);
    EXPECT_TRUE(tracks.at(8).touching);  // the other slot's contact is untouched
    EXPECT_EQ(tracks.at(8).userDataA, 9u);
    // A contact beginning on another slot takes the ended one's record: slot 3 stays off.
    tracks.begin(5, touching(6, 7, 11));
    EXPECT_FALSE(tracks.at(3).touching);
    EXPECT_EQ(tracks.at(5).a.index, 6u);
    EXPECT_EQ(tracks.at(8).a.index, 4u);
    tracks.end(3);  // ending a slot with no contact changes nothing
    EXPECT_TRUE(tracks.at(5).touching);
    // A slot past the cover is covered when its contact begins.
    tracks.begin(20, touching(8, 9, 13));
    EXPECT_EQ(tracks.slots(), 21u);
    EXPECT_TRUE(tracks.at(20).touching);
    tracks.reset(4);
    EXPECT_EQ(tracks.slots(), 4u);
    for (std::uint32_t slot : {3u, 5u, 8u, 20u}) EXPECT_FALSE(tracks.at(slot).touching) << slot;
}

}  // namespace
}  // namespace cyclone::test
