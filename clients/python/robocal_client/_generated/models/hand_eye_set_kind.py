from enum import StrEnum

class HandEyeSetKind(StrEnum):
    HAND_EYE = "hand_eye"

    def __str__(self) -> str:
        return str(self.value)
