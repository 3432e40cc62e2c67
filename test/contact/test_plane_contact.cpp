#include <gtest/gtest.h>
#include "virtual_go/contact/plane_contact.h"
TEST(PlaneContact, Placeholder) {}
