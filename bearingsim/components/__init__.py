"""Component libraries: rotational mechanics, bearing elements, motors."""
