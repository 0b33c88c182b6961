from enum import StrEnum

class Measurement(StrEnum):
    POSE = "pose"
    POSITION = "position"

    def __str__(self) -> str:
        return str(self.value)
