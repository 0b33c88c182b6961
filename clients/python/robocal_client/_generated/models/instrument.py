from enum import StrEnum

class Instrument(StrEnum):
    CAMERA = "camera"
    STAGE = "stage"
    TRACKER = "tracker"

    def __str__(self) -> str:
        return str(self.value)
