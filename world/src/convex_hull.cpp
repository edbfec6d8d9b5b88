// Implemented in the collision work; placeholder so the tree configures.
